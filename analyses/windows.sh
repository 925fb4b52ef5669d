#!/usr/bin/env bash
# Regenerates results/windows: certified bounds, precision study, iterator check.
# Usage: analyses/windows.sh [path/to/btob]   (run from the repository root; called by analyses/run_all.sh)
set -euo pipefail
BTOB=${1:-build/release/btob}
OUT=results/windows
mkdir -p "$OUT"
# Table B.1 with exact certificates (n = 1..100, 12 decimals; ~2 s: Descartes root counts, Sturm as fallback).
"$BTOB" windows bounds --n 1..100 --digits 12 --certify > "$OUT/bounds_certified.csv.tmp"
mv "$OUT/bounds_certified.csv.tmp" "$OUT/bounds_certified.csv"
# Its manifest (the command prints to stdout and writes none): btob_manifest is built beside btob.
"$(dirname "$BTOB")/btob_manifest" "$OUT/bounds_certified.json" \
  "$BTOB windows bounds --n 1..100 --digits 12 --certify > $OUT/bounds_certified.csv" bounds_certified.csv
# Precision study (precision.csv, precision_summary.csv, precision.json, precision.png).
"$BTOB" windows precision --n 1..150 --out "$OUT"
# The iterator inside and below each window (verify.csv + verify.json).
"$BTOB" windows verify --n 2..125 --out "$OUT" --quiet
