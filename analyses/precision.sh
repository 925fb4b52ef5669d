#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/precision: speed against accuracy per precision and algorithm, against a
# 256-digit MPFR run of the same orbits (tradeoff.csv, tradeoff.png, manifest).
# Usage: analyses/precision.sh [path/to/btob]   (run from the repository root; ~1 minute on 2 cores)
set -euo pipefail
BTOB=${1:-build/release/btob}
"$BTOB" precision --iterations 20000 --out results/precision
