#!/usr/bin/env bash
# Builds the Release tree and runs every benchmark; results go to build/bench-results/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" release > /dev/null
out="$root/build/bench-results"
mkdir -p "$out"
for b in "$root"/build/release/bench/bench_*; do
  name=$(basename "$b")
  echo "== $name"
  case "$name" in
    bench_cholmod_threads|bench_assembly|bench_contact) "$b" | tee "$out/$name.txt" ;;  # plain programs, ratios
    *) "$b" --benchmark_min_time=0.5 | tee "$out/$name.txt" ;;      # Google Benchmark
  esac
done
