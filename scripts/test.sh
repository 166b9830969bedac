#!/usr/bin/env bash
# The README's test command (and all that .ci/run does): installs what is missing, checks
# formatting, builds Release with warnings as errors and runs every test, then builds Debug
# with AddressSanitizer + UndefinedBehaviorSanitizer and runs the unit and verification tests
# (except those labelled slow: convergence sweeps that only make sense optimised).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
phase() { echo; echo "== $1 ($(( $(date +%s) - start )) s)"; }
jobs=$(nproc 2>/dev/null || echo 2)

phase "dependencies"
bash scripts/deps.sh --tests
mkdir -p build

phase "format"
bash scripts/check_format.sh

phase "release build (-Werror)"
bash scripts/build.sh release > build/build-release.log 2>&1 ||
  { tail -80 build/build-release.log; echo "release build failed" >&2; exit 1; }

phase "release tests"
ctest --test-dir build/release --output-on-failure -j "$jobs" --timeout 900

phase "sanitizer build (ASan + UBSan, Debug)"
bash scripts/build.sh asan > build/build-asan.log 2>&1 ||
  { tail -80 build/build-asan.log; echo "sanitizer build failed" >&2; exit 1; }

phase "sanitizer tests (unit, verification)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
export LSAN_OPTIONS=suppressions=$root/tests/tools/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build/asan --output-on-failure -j "$jobs" -L 'unit|verification' -LE slow --timeout 900

phase "done"
