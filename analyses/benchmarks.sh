#!/usr/bin/env bash
# Throughput report: runs the Google Benchmark programs and writes results/benchmarks/ (JSON + plot).
# Usage: analyses/benchmarks.sh [BTOB_BINARY]   (the benchmark programs are found next to it)
# Quote ratios measured in one run: the machine is shared and absolute times drift.
set -euo pipefail
cd "$(dirname "$0")/.."
btob="${1:-build/release/btob}"
bdir="$(dirname "$btob")/benchmarks"
out=results/benchmarks
mkdir -p "$out"
for bm in "$bdir"/bm_iterate; do
  name=$(basename "$bm")
  tmp="$out/$name.json.tmp-$$"
  "$bm" --benchmark_filter='^(core_clock|scalar_loop|batched|fig41_density)' --benchmark_min_time=1 \
        --benchmark_out="$tmp" --benchmark_out_format=json >/dev/null
  mv "$tmp" "$out/$name.json"
done
/usr/bin/python3 analyses/plot/benchmarks.py "$out/bm_iterate.json" "$out/bm_iterate.png"
