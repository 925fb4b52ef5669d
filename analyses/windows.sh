#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/windows: certified bounds (Table B.1), the polynomials Q_n (Table B.2), precision study,
# iterator check.
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
# Table B.2: Q_n for n = 1..10, developed and factorised, in exact rationals (and its manifest).
"$BTOB" windows poly --n 1..10 --quiet > "$OUT/table_B2.txt.tmp"
mv "$OUT/table_B2.txt.tmp" "$OUT/table_B2.txt"
"$(dirname "$BTOB")/btob_manifest" "$OUT/table_B2.json" "$BTOB windows poly --n 1..10 > $OUT/table_B2.txt" table_B2.txt
# Precision study (precision.csv, precision_summary.csv, precision.json, precision.png).
"$BTOB" windows precision --n 1..150 --out "$OUT"
# The iterator inside and below each window (verify.csv + verify.json).
"$BTOB" windows verify --n 2..125 --out "$OUT" --quiet
