#!/usr/bin/env bash
# The README's run command: installs what is missing, builds the program `nmm` alone (not
# the tests and benchmarks: scripts/test.sh builds those, in the same tree build/release),
# runs it with the given arguments (none: the bundled example).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/deps.sh"
mkdir -p "$root/build"
[ -x "$root/build/release/nmm" ] ||
  echo "run.sh: building nmm (the first time takes a few minutes; log in build/build-release.log)" >&2
bash "$root/scripts/build.sh" release nmm > "$root/build/build-release.log" 2>&1 ||
  { tail -50 "$root/build/build-release.log"; echo "build failed: full log in build/build-release.log" >&2; exit 1; }
exec "$root/build/release/nmm" "$@"
