#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/patterns: the atlas of stable periodic patterns up to length 12 and its
# check against the iterator (atlas.csv, atlas_detected.csv, atlas_long_windows.csv, atlas_missed.csv, atlas.h5,
# atlas.json, atlas.png).
# Usage: analyses/patterns.sh [path/to/btob]   (run from the repository root; a few minutes on 2 cores)
set -euo pipefail
BTOB=${1:-build/release/btob}
"$BTOB" pattern atlas --max-length 12 --out results/patterns
