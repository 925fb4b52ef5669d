#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The error contract of transfer and transfer-r, as tests/cli_errors.sh checks it for the others:
# bad input gets a one-line error naming the field, exit status 2, and no output file written.
# Usage: cli_errors_transfer.sh PATH/TO/btob
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

t=(transfer --out "$out/t" --no-plot --quiet --measure-orbits 0)
expect_error "boxes" "${t[@]}" --r 0.2 --boxes 0x10
expect_error "boxes" "${t[@]}" --r 0.2 --boxes 10x0
expect_error "boxes" "${t[@]}" --r 0.2 --boxes 20000x20000
expect_error "boxes" "${t[@]}" --r 0.2 --boxes 10000x10000 --samples 16
expect_error "boxes" "${t[@]}" --r 0.2 --boxes 8
expect_error "boxes" "${t[@]}" --r 0.2 --boxes axb
expect_error "eigenvalues" "${t[@]}" --r 0.2 --boxes 4x4 --tv-bins 4 --eigenvalues 17
expect_error "eigenvalues" "${t[@]}" --r 0.2 --eigenvalues -1
# --eigenvalues 0 (no spectrum, only the basins) needs an attractor and no spectral cross-check.
expect_error "eigenvalues" "${t[@]}" --r 0.15 --eigenvalues 0
expect_error "eigenvalues" "${t[@]}" --r 0.15 --eigenvalues 0 --cycle 132312
expect_error "eigenvalues" "${t[@]}" --r 0.2 --eigenvalues 0 --check-whole
expect_error "r" "${t[@]}" --r 0
expect_error "r" "${t[@]}" --r 1
expect_error "r" "${t[@]}" --r -0.5
expect_error "r" "${t[@]}" --r nan
expect_error "samples" "${t[@]}" --r 0.2 --samples 0
expect_error "domain" "${t[@]}" --r 0.2 --domain disc
expect_error "route" "${t[@]}" --r 0.2 --route gpu
expect_error "near-one" "${t[@]}" --r 0.2 --near-one 0
expect_error "tv-bins" "${t[@]}" --r 0.2 --boxes 30x30 --tv-bins 64
expect_error "w1-range" "${t[@]}" --r 0.2 --w1-range 3,1
expect_error "cycle" "${t[@]}" --r 0.2 --cycle 14
expect_error "threads" "${t[@]}" --r 0.2 --threads -1
[ -e "$out/t" ] && [ -n "$(ls -A "$out/t")" ] && { echo "FAIL: refused transfer runs wrote $(ls "$out/t")"; fail=1; }

tr=(transfer-r --out "$out/tr" --no-plot --quiet)
expect_error "r-min" "${tr[@]}" --r-min 0 --r-max 0.5
expect_error "r-max" "${tr[@]}" --r-min 0.3 --r-max 0.2
expect_error "r-max" "${tr[@]}" --r-min 0.3 --r-max 1
expect_error "r-count" "${tr[@]}" --r-count 0
expect_error "boxes" "${tr[@]}" --boxes 0x0
expect_error "eigenvalues" "${tr[@]}" --boxes 3x3 --eigenvalues 10
expect_error "eigenvalues" "${tr[@]}" --eigenvalues 0
expect_error "peripheral" "${tr[@]}" --peripheral 1
[ -e "$out/tr" ] && [ -n "$(ls -A "$out/tr")" ] && { echo "FAIL: refused transfer-r runs wrote $(ls "$out/tr")"; fail=1; }

# A valid small run writes its files and no temporaries.
"$btob" "${t[@]}" --r 0.15 --boxes 16x16 --samples 4 --eigenvalues 4 --tv-bins 16 >/dev/null 2>&1 || { echo "FAIL: a valid transfer run failed"; fail=1; }
[ -s "$out/t/spectrum.csv" ] || { echo "FAIL: $out/t/spectrum.csv missing"; fail=1; }
[ -n "$(find "$out/t" -name "*tmp*")" ] && { echo "FAIL: temporary files left behind"; fail=1; }
# Without a spectrum: the basins and cycles, none of the spectral tables.
"$btob" transfer --out "$out/t0" --no-plot --quiet --r 0.21 --boxes 16x16 --samples 4 --eigenvalues 0 --tv-bins 16 \
  --cycle 1322 >/dev/null 2>&1 || { echo "FAIL: a valid transfer run without a spectrum failed"; fail=1; }
[ -s "$out/t0/basins.csv" ] && [ -s "$out/t0/cycles.csv" ] || { echo "FAIL: basins.csv or cycles.csv missing (eigenvalues 0)"; fail=1; }
[ -e "$out/t0/spectrum.csv" ] || [ -e "$out/t0/components.csv" ] && { echo "FAIL: spectral tables written with eigenvalues 0"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "cli_errors_transfer: all checks passed"; fi
exit $fail
