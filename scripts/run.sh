#!/usr/bin/env bash
# The README's run command: installs what is missing, builds, runs `nmm` with the given
# arguments (none: the bundled example).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/deps.sh"
mkdir -p "$root/build"
bash "$root/scripts/build.sh" release > "$root/build/build-release.log" 2>&1 ||
  { tail -50 "$root/build/build-release.log"; echo "build failed: full log in build/build-release.log" >&2; exit 1; }
exec "$root/build/release/nmm" "$@"
