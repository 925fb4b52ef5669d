#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/attractors/**: basin maps at the r values of Section 6.2 / Table 6.1 and the basin
# fractions across r compared with Table 6.1.  Usage: analyses/attractors.sh path/to/btob [threads]
set -euo pipefail
BTOB=${1:?usage: analyses/attractors.sh path/to/btob [threads]}
THREADS=${2:-2}
cd "$(dirname "$0")/.."
OUT=results/attractors
mkdir -p "$OUT"
# Fractions are of a measure, named in every output.  The default, sphere:NxM, is the uniform measure on
# the sphere of directions of the domain (an equal-area grid); strip:NxM grids count Lebesgue measure on their
# rectangle of the plane x - z = 1 (an explicit choice: they print the share of the sphere measure they leave out).
for r in 0.05 0.1 0.15 0.172 0.2 0.21 0.24 0.3 0.58; do
  "$BTOB" basins --r "$r" --grid sphere:300x300 --replicates 1 --seed 1 --threads "$THREADS" --out "$OUT/basins_sphere_r$r"
done
# The speed target: 1000 x 1000 at r = 0.2 (two replicate grids shifted by random fractions of a cell).
"$BTOB" basins --r 0.2 --grid strip:1000x1000 --replicates 2 --seed 1 --threads "$THREADS" --out "$OUT/basins_r0.2"
# Coexistence and single-basin cases of Table 6.1 (400 x 400, two replicates).
for r in 0.05 0.1 0.15 0.172 0.21 0.24 0.3 0.58; do
  "$BTOB" basins --r "$r" --grid strip:400x400 --replicates 2 --seed 1 --threads "$THREADS" --out "$OUT/basins_r$r"
done
# Wider strip at r = 0.2: the two far points per period of 132^3312^3 (Figure 6.10 rescaled).
"$BTOB" basins --r 0.2 --grid strip:600x300 --w1-range -30,30 --replicates 0 --threads "$THREADS" --out "$OUT/basins_r0.2_wide"
# Basin fractions at the r values of Table 6.1 in [0.1, 0.6], 2000 random orbits each (the paper: 10): random:N is
# uniform on the sphere of directions of the domain, the same measure as sphere:NxM.
"$BTOB" basins-r --table --grid random:2000 --seed 1 --boundary-grid sphere:300x300 --threads "$THREADS" --out "$OUT/basins_r"
# Table 6.1 against candidate initial distributions and the paper's detection rule (results/attractors/table_6_1):
# the Python module built beside the binary, a few minutes on 2 cores.
PYTHONPATH="$(cd "$(dirname "$BTOB")" && pwd)/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 \
  analyses/table_6_1_candidates.py --threads "$THREADS" --out "$OUT/table_6_1"
