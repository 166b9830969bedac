#!/usr/bin/env bash
# Fails on any clang-format difference in our sources. The version is pinned to 14
# (Debian 12): another major version formats differently and would make CI flap.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
formatter=$(command -v clang-format-14 || command -v clang-format || true)
[ -n "$formatter" ] || { echo "format: clang-format-14 not found (scripts/deps.sh --tests installs it)" >&2; exit 1; }
version=$("$formatter" --version | sed -E 's/.*version ([0-9]+).*/\1/')
[ "$version" = 14 ] || { echo "format: need clang-format 14, found $version ($formatter)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' 2>/dev/null ||
                     find mesh manifold contact solver io tests bench examples -name '*.[ch]pp')
[ ${#files[@]} -gt 0 ] || exit 0
if ! "$formatter" --dry-run -Werror "${files[@]}" 2> build-format.log; then
  grep -E '^[^ ].*(error|warning):' build-format.log | head -20
  echo "format: differences found; run: $formatter -i \$(git ls-files '*.cpp' '*.hpp')" >&2
  rm -f build-format.log
  exit 1
fi
rm -f build-format.log
echo "format: ok (${#files[@]} files, $("$formatter" --version | head -1))"
