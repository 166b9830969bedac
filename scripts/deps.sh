#!/usr/bin/env bash
# Installs the Debian 12 packages the build and tests need, only those missing.
# Usage: scripts/deps.sh [--tests]   (--tests adds the test/benchmark-only packages)
set -euo pipefail
packages=(g++ cmake make ninja-build
          libeigen3-dev libcgal-dev libgmsh-dev libsuitesparse-dev libopenblas-dev
          libvtk9-dev libtomlplusplus-dev libcli11-dev
          libgtest-dev libgmock-dev libbenchmark-dev)
if [ "${1:-}" = "--tests" ]; then
  # lld: CMakeLists.txt links with it when present (the sanitizer build's links 3x faster);
  # it needs the same libllvm14 as clang-format-14. python3: the check that every output
  # file is well-formed XML (tests/tools/check_output_xml.py; standard library only).
  # ccache: a second run of the test command (CI on the same machine, a fresh clone anywhere:
  # scripts/build.sh makes its paths relative to the checkout) compiles only what changed.
  packages+=(clang-format-14 lld python3 ccache)
fi
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "deps: installing ${missing[*]}"
run_as_root=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo > /dev/null; then run_as_root=(sudo); else
    echo "deps: missing packages ${missing[*]}; run as root: apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${run_as_root[@]}" apt-get update -qq
"${run_as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
echo "deps: installed ${#missing[@]} packages"
