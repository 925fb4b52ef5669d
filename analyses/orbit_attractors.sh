#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/orbit_attractors: r against attractor.  `btob lyapunov-map --attractors` over r in
# [0.0718, 0.45] (just above 7 - 4 sqrt 3, where collapse ends) with 64 random orbits per r: each orbit's exponents
# and its attractor (btob classify with the same transient and iterations), then the share of the orbits that
# reached each attractor at each r, with the windows of (ab)^n(cb)^n shaded.
#   orbit_attractors.h5, .json, _summary.csv, .png   the map and its attractors (lyapunov_map.py's figure)
#   attractors_r.png                                  analyses/plot/orbit_attractors.py on the HDF5 file alone
# Usage: analyses/orbit_attractors.sh [path/to/btob]   (run from the repository root; called by analyses/run_all.sh)
set -euo pipefail
BTOB=${1:-build/release/btob}
OUT=results/orbit_attractors
"$BTOB" lyapunov-map --r-min 0.0718 --r-max 0.45 --r-count 400 --grid random:64 --seed 1 --transient 2000 \
  --iterations 3000 --overlay thresholds windows --attractors --out "$OUT" --name orbit_attractors \
  --title "Attractor reached by each orbit against r" --quiet
/usr/bin/python3 analyses/plot/orbit_attractors.py "$OUT/orbit_attractors.h5" "$OUT/attractors_r.png"
