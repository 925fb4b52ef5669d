#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates everything in results/ from the scenes and analyses of this folder.
# Usage: analyses/run_all.sh [BTOB_BINARY]      (default: build/release/btob)
# Each result folder gets its data (HDF5/CSV), the PNG and a manifest (commit, command, seed, precision).
set -euo pipefail
cd "$(dirname "$0")/.."
btob="${1:-build/release/btob}"
[ -x "$btob" ] || { echo "run_all: $btob not found; build first: cmake --preset release && cmake --build --preset release" >&2; exit 2; }
start=$(date +%s)
for scene in analyses/scenes/*.toml; do
  name=$(basename "$scene" .toml)
  t0=$(date +%s%N)
  "$btob" run "$scene"
  printf 'run_all: %-12s %6d ms\n' "$name" $(( ($(date +%s%N) - t0) / 1000000 ))
done
# Further analyses: one script per module, analyses/<module>.sh, each taking the btob binary.
for script in analyses/*.sh; do
  case "$(basename "$script")" in run_all.sh) continue ;; esac
  echo "run_all: $script"
  bash "$script" "$btob"
done
# The gallery of every figure (results/README.md), last: it reads the manifests written above.
/usr/bin/python3 analyses/gallery.py .
echo "run_all: done in $(( $(date +%s) - start )) s"
