#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Figure 4.1 in float and in double, in log10(theta): where does float's diagram differ?  Writes
# results/float_vs_double/ (both data sets, per-r distances as CSV, and a comparison figure).
# Usage: analyses/float_vs_double.sh [path/to/btob]
set -euo pipefail
BTOB=${1:-build/release/btob}
OUT=results/float_vs_double
mkdir -p "$OUT"
for p in float double; do
  "$BTOB" bifurcation --r-min 0.0717 --r-max 0.1717 --r-count 5000 --iterations 5000 --tail 100 --grid paper \
    --bins 700 --log --range -60 0.25 --precision "$p" --name "fig4_1_$p" --title "Figure 4.1 in $p" --out "$OUT" --no-plot --quiet
done
/usr/bin/python3 analyses/plot/float_vs_double.py "$OUT/fig4_1_float.h5" "$OUT/fig4_1_double.h5" "$OUT"
