#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The error contract of classify, basins and basins-r, as tests/cli_errors.sh checks it for the others:
# bad input gets a one-line error naming the field, exit status 2, and no output file written.
# Usage: cli_errors_attractors.sh PATH/TO/btob
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

# btob classify (one orbit)
c=(classify --point 1,-1,-0.5)
expect_error "r" "${c[@]}" --r 1.2
expect_error "r" "${c[@]}" --r nan
expect_error "r" "${c[@]}" --r 0
expect_error "point" classify --r 0.2 --point 1,-1,0.5
expect_error "point" classify --r 0.2 --point 0,0,0
expect_error "point" classify --r 0.2 --point 1,-1
expect_error "max-period" "${c[@]}" --r 0.2 --max-period 0
expect_error "return-tol" "${c[@]}" --r 0.2 --return-tol 0.5
expect_error "point-tol" "${c[@]}" --r 0.2 --point-tol 1
expect_error "window" "${c[@]}" --r 0.2 --iterations 10
expect_error "rotation-tol" "${c[@]}" --r 0.2 --rotation-tol 0

# btob basins: every refused request leaves no file behind
b=(basins --out "$out/b" --no-plot --quiet)
expect_error "grid" "${b[@]}" --r 0.2 --grid strip:0x10
expect_error "grid" "${b[@]}" --r 0.2 --grid strip:100000x100000
expect_error "grid" "${b[@]}" --r 0.2 --grid foo:3
expect_error "r" "${b[@]}" --r 0
expect_error "r" "${b[@]}" --r inf
expect_error "w1-range" "${b[@]}" --r 0.2 --w1-range 3,1
expect_error "collapse-theta" "${b[@]}" --r 0.2 --collapse-theta 2
expect_error "lyap-blocks" "${b[@]}" --r 0.2 --lyap-blocks 1
expect_error "replicates" "${b[@]}" --r 0.2 --replicates 101
expect_error "entropy-box" "${b[@]}" --r 0.2 --entropy-box 0
expect_error "entropy-box" "${b[@]}" --r 0.2 --entropy-box 1001
[ -e "$out/b" ] && [ -n "$(ls -A "$out/b")" ] && { echo "FAIL: refused basins runs wrote $(ls "$out/b")"; fail=1; }

# btob basins-r
expect_error "r-values" basins-r --grid random:10 --out "$out/br" --no-plot
expect_error "boundary-grid" basins-r --r-values 0.2 --grid random:10 --boundary-grid sphere:0x4 --out "$out/br" --no-plot
expect_error "boundary-replicates" basins-r --r-values 0.2 --grid random:10 --boundary-replicates 101 --out "$out/br" --no-plot
expect_error "entropy-box" basins-r --r-values 0.2 --grid random:10 --entropy-box 0 --out "$out/br" --no-plot
[ -e "$out/br" ] && [ -n "$(ls -A "$out/br")" ] && { echo "FAIL: refused basins-r run wrote $(ls "$out/br")"; fail=1; }

# A valid small run writes its files and no temporaries.
"$btob" "${b[@]}" --r 0.15 --grid strip:8x8 --replicates 0 >/dev/null 2>&1 || { echo "FAIL: a valid basins run failed"; fail=1; }
[ -s "$out/b/basins_fractions.csv" ] || { echo "FAIL: $out/b/basins_fractions.csv missing"; fail=1; }
[ -s "$out/b/basins_boundary.csv" ] || { echo "FAIL: $out/b/basins_boundary.csv missing"; fail=1; }
[ -n "$(find "$out/b" -name "*tmp*")" ] && { echo "FAIL: temporary files left behind"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "cli_errors_attractors: all checks passed"; fi
exit $fail
