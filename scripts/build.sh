#!/usr/bin/env bash
# Configures and builds one build tree. Usage: scripts/build.sh release|asan
# release: build/release, optimised, warnings as errors (the tree `nmm` and the tests use).
# asan:    build/asan, Debug with AddressSanitizer + UndefinedBehaviorSanitizer, no benchmarks
#          and no regression tests (scripts/test.sh runs the unit and verification labels there).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
kind=${1:-release}
jobs=$(nproc 2>/dev/null || echo 2)
case "$kind" in
  release) args=(-DCMAKE_BUILD_TYPE=Release -DNMM_WARNINGS_AS_ERRORS=ON) ;;
  asan) args=(-DCMAKE_BUILD_TYPE=Debug -DNMM_SANITIZE=ON -DNMM_WARNINGS_AS_ERRORS=ON -DNMM_BUILD_BENCH=OFF
              -DNMM_BUILD_REGRESSION_TESTS=OFF) ;;
  *) echo "usage: scripts/build.sh release|asan" >&2; exit 2 ;;
esac
mkdir -p "$root/build"
cmake -S "$root" -B "$root/build/$kind" "${args[@]}" > "$root/build/configure-$kind.log" 2>&1 ||
  { cat "$root/build/configure-$kind.log"; exit 1; }
cmake --build "$root/build/$kind" -j "$jobs"
