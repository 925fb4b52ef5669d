#!/usr/bin/env bash
# Regenerates results/stats (issue 7): C_N for a periodic (r = 0.15), a quasi-periodic (r = 0.2, on an
# invariant curve of the P2 rotation) and an apparently chaotic (r = 0.11) orbit; empirical measures of the
# 32 orbits of the Section 4 grid at r = 0.15 (one basin, 1133) and of orbits on several invariant curves
# at r = 0.2.   Usage: analyses/stats.sh [path/to/btob]
set -euo pipefail
BTOB=${1:-build/release/btob}
OUT=results/stats
"$BTOB" correlate --r 0.15 --observable phi --n-max 1000 --iterations 1000000 --out "$OUT" --name correlation_periodic_r0.15
"$BTOB" correlate --r 0.2 --point 1,0.02,-1 --observable phi --n-max 1000 --iterations 1000000 --out "$OUT" --name correlation_quasiperiodic_r0.2
"$BTOB" correlate --r 0.11 --observable phi --n-max 1000 --iterations 1000000 --out "$OUT" --name correlation_chaotic_r0.11
"$BTOB" measure --r 0.15 --grid paper --iterations 100000 --transient 10000 --out "$OUT" --name measure_r0.15
"$BTOB" measure --r 0.2 --grid "1,0.01,-1;1,0.03,-1;1,0.05,-1;1,0.07,-1" --iterations 100000 --transient 1000 --out "$OUT" --name measure_r0.2_curves
