#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/transfer/** (Section 8): Ulam's transfer operator of P_r at r = 0.15, 0.1, 0.21, 0.3, 0.11 (a
# sink, a window, sinks with invariant curves, chaos), each at three resolutions or more, and the peripheral spectrum
# across [0.07, 0.6] at three resolutions; then the
# convergence tables (and the basins' extrapolation).  Usage: analyses/transfer.sh path/to/btob [threads]
set -euo pipefail
BTOB=${1:?usage: analyses/transfer.sh path/to/btob [threads]}
THREADS=${2:-2}
cd "$(dirname "$0")/.."
OUT=results/transfer
mkdir -p "$OUT"
run() {  # run NAME R BOXES TV_BINS CYCLES [extra flags...]
  local name=$1 r=$2 boxes=$3 tv=$4 cycles=$5
  shift 5
  "$BTOB" transfer --r "$r" --boxes "$boxes" --samples 64 --eigenvalues 24 --tv-bins "$tv" ${cycles:+--cycle "$cycles"} \
    --threads "$THREADS" --out "$OUT/$name" "$@"
}
basins() {  # basins NAME R BOXES CYCLES: the basins from the Ulam graph alone (--eigenvalues 0: no spectrum)
  local name=$1 r=$2 boxes=$3 cycles=$4
  "$BTOB" transfer --r "$r" --boxes "$boxes" --samples 64 --eigenvalues 0 --tv-bins 32 --cycle "$cycles" \
    --threads "$THREADS" --out "$OUT/$name"
}
# Sinks: r = 0.15 (1133; 512 x 512 is the timing target) and r = 0.1 (111333, inside the window n = 3).
for b in 128 256 512; do run "r0.15_${b}" 0.15 "${b}x${b}" 32 1133; done
# r = 0.1's sink lies 0.0145 rad in atan(w1) from the P2/P3 branch line (2.4 boxes at 512^2): Ulam's smearing
# crosses it below 1024^2 (the closed class is then the whole chart), so a fourth resolution (~4 min, 1.8 GB).
for b in 128 256 512 1024; do run "r0.1_${b}" 0.1 "${b}x${b}" 32 111333; done
# Coexistence: r = 0.21 (132^2, 312^2, 132^3312^3 and the P2 invariant curves); basins from the Ulam graph against
# the counted fractions of results/attractors/basins_r0.21 (transfer_summary.py).  Not 512^2 with the spectrum: its
# Arnoldi runs on the 198 225-box closed class took 67 s for the 24 leading eigenvalues, then over 8 min more without
# finishing (load 10).
for b in 64 128 256; do run "r0.21_${b}" 0.21 "${b}x${b}" 32 "1322,3122,132^3312^3"; done
# The basins alone at three finer resolutions (no spectrum: the absorption solves need only the matrix; 2048^2:
# ~4 min, ~2.3 GB).
for b in 512 1024 2048; do basins "r0.21_${b}" 0.21 "${b}x${b}" "1322,3122,132^3312^3"; done
# The P2 region: r = 0.3 (132312 and the P2 curves; rotation eigenvalues exp(i k beta)).
for b in 64 128 256; do run "r0.3_${b}" 0.3 "${b}x${b}" 32 132312; done
for b in 512 1024 2048; do basins "r0.3_${b}" 0.3 "${b}x${b}" 132312; done
# Chaos: r = 0.11 (the Ulam density against the empirical measure of 256 orbits).
for b in 64 128 256; do run "r0.11_${b}" 0.11 "${b}x${b}" 32 ""; done
# The peripheral spectrum across r at three resolutions.
for b in 32 64 128; do
  "$BTOB" transfer-r --r-min 0.07 --r-max 0.6 --r-count 107 --boxes "${b}x${b}" --samples 16 --eigenvalues 24 \
    --peripheral 0.01 --threads "$THREADS" --out "$OUT/r_scan_${b}"
done
"${BTOB_PYTHON:-/usr/bin/python3}" analyses/transfer_summary.py "$OUT"
# The summary's manifest (the script's tables are no command's output): btob_manifest is built beside btob.
"$(dirname "$BTOB")/btob_manifest" "$OUT/summary.json" "analyses/transfer.sh $BTOB $THREADS" \
  convergence.csv basins_convergence.csv basins_extrapolation.csv basins_convergence.png gap_r.csv gap_r.png
