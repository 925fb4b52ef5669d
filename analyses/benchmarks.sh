#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Throughput report: runs the Google Benchmark programs and writes results/benchmarks/ (JSON + plot).
# Usage: analyses/benchmarks.sh [BTOB_BINARY]   (the benchmark programs are found next to it)
# Quote ratios measured in one run: the machine is shared and absolute times drift.
set -euo pipefail
cd "$(dirname "$0")/.."
btob="${1:-build/release/btob}"
bdir="$(dirname "$btob")/benchmarks"
out=results/benchmarks
mkdir -p "$out"
# bm_iterate: the iterator against the scalar loop of Appendix A.2 (plotted below); the others: Lyapunov
# exponents (scalar QR route in every precision, batched map), C_N (FFT against the direct sum, N = 1e6,
# n_max = 1e5), attractor classification (points per second) and the window certificates (Descartes against
# Sturm on the same polynomials, bounds at 512 decimals).  Smoke cases are left out.
for name in bm_iterate bm_lyapunov bm_stats bm_attractors bm_windows; do
  bm="$bdir/$name"
  [ -x "$bm" ] || { echo "benchmarks: $bm not built" >&2; exit 2; }
  filter='^[^s]'  # everything but the smoke/... cases
  [ "$name" = bm_iterate ] && filter='^(core_clock|scalar_loop|batched|fig41_density|fig41_plain)'
  # The programs whose workloads are quoted against the plain kernel run five repetitions in random interleaving
  # (bm_iterate's fig41 pair, and bm_lyapunov's and bm_attractors' plain_reference, benchmarks/plain_reference.hpp):
  # a workload and its reference are measured in the same minutes, and analyses/benchmark_ratios.py divides their best
  # and their median repetitions.
  reps=()
  case "$name" in bm_iterate|bm_lyapunov|bm_attractors)
    reps=(--benchmark_repetitions=5 --benchmark_enable_random_interleaving=true) ;;
  esac
  tmp="$out/$name.json.tmp-$$"
  "$bm" --benchmark_filter="$filter" --benchmark_min_time=1 "${reps[@]}" --benchmark_out="$tmp" \
    --benchmark_out_format=json >/dev/null
  mv "$tmp" "$out/$name.json"
done
/usr/bin/python3 analyses/plot/benchmarks.py "$out/bm_iterate.json" "$out/bm_iterate.png"
/usr/bin/python3 analyses/benchmark_ratios.py "$out"
# One manifest for the run (the benchmark programs link the same libraries as btob, built from the same tree).
"$(dirname "$btob")/btob_manifest" "$out/manifest.json" "analyses/benchmarks.sh $btob" \
  bm_iterate.json bm_lyapunov.json bm_stats.json bm_attractors.json bm_windows.json bm_iterate.png ratios.csv
