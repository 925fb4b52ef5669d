#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The error contract of the Lyapunov and hyperbolicity subcommands, as tests/cli_errors.sh checks it
# for the others: bad input gets a one-line error naming the field, exit status 2, and no output file written.
# Usage: cli_errors_lyapunov.sh PATH/TO/btob
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

# btob lyapunov, lyapunov-map and lyapunov-strip: bad r and r ranges, points, grids, lengths, blocks, precisions and
# threads, beyond the cases of cli_errors.sh.
p=(lyapunov --point 1,0.1,-1 --iterations 100 --transient 10)
expect_error "r" "${p[@]}" --r 1.2
expect_error "r" "${p[@]}" --r nan
expect_error "blocks" "${p[@]}" --r 0.3 --blocks 1
expect_error "reorthonormalise" "${p[@]}" --r 0.3 --reorthonormalise 0
expect_error "precision" "${p[@]}" --r 0.3 --precision quad
expect_error "point" lyapunov --r 0.3 --point 1,2 --iterations 100 --transient 10
expect_error "point" lyapunov --r 0.3 --point 0,1,0 --iterations 100 --transient 10

# btob lyapunov-map
m=(lyapunov-map --out "$out/m" --r-count 3 --iterations 100 --transient 10 --no-plot --quiet)
expect_error "r-min" "${m[@]}" --r-min 0
expect_error "r-max" "${m[@]}" --r-max 1.2
expect_error "r-count" "${m[@]}" --r-count -3
expect_error "iterations" "${m[@]}" --iterations 0
expect_error "transient" "${m[@]}" --transient 200
expect_error "blocks" "${m[@]}" --blocks 1
expect_error "grid" "${m[@]}" --grid "1,0.1,1"
expect_error "precision" "${m[@]}" --precision quad
expect_error "threads" "${m[@]}" --threads -1
expect_error "attractors: got with precision float" "${m[@]}" --attractors --precision float
expect_error "attractors: got with transient 0" "${m[@]}" --attractors --transient 0
[ -e "$out/m" ] && [ -n "$(ls -A "$out/m")" ] && { echo "FAIL: lyapunov-map output written despite errors"; fail=1; }

# btob lyapunov-strip
s=(lyapunov-strip --out "$out/s" --grid strip:4x4 --iterations 100 --transient 10 --no-plot --quiet)
expect_error "r" "${s[@]}" --r 1.2
expect_error "grid" "${s[@]}" --grid strip:0x4
expect_error "grid" "${s[@]}" --grid strip:4x4:1:-1
expect_error "iterations" "${s[@]}" --iterations 0
[ -e "$out/s" ] && [ -n "$(ls -A "$out/s")" ] && { echo "FAIL: lyapunov-strip output written despite errors"; fail=1; }

# btob hyperbolicity (item 5)
h=(hyperbolicity --out "$out/h" --grid strip:8x4 --no-plot --quiet)
expect_error "r" "${h[@]}" --r 0
expect_error "r" "${h[@]}" --r 1
expect_error "grid" "${h[@]}" --r 0.3 --grid strip:0x4
expect_error "grid" "${h[@]}" --r 0.3 --grid paper
expect_error "grid" "${h[@]}" --r 0.3 --grid strip:200000x200000
expect_error "w1-range" "${h[@]}" --r 0.3 --w1-range 1,-1
expect_error "w1-range" "${h[@]}" --r 0.3 --w1-range 1
expect_error "w1-range" "${h[@]}" --r 0.3 --w1-range a,b
expect_error "w1-range" "${h[@]}" --r 0.3 --w1-range 0,inf
[ -e "$out/h" ] && [ -n "$(ls -A "$out/h")" ] && { echo "FAIL: hyperbolicity output written despite errors"; fail=1; }

# btob hyperbolicity-orbits (item 5)
o=(hyperbolicity-orbits --out "$out/o" --r-count 2 --iterations 100 --transient 10 --backward 10 --no-plot --quiet)
expect_error "r-min" "${o[@]}" --r-min 0
expect_error "r-max" "${o[@]}" --r-max 1.5
expect_error "r-count" "${o[@]}" --r-count 0
expect_error "iterations" "${o[@]}" --iterations 5
expect_error "transient" "${o[@]}" --transient -1
expect_error "backward" "${o[@]}" --backward 0
expect_error "bins" "${o[@]}" --bins 0
expect_error "grid" "${o[@]}" --grid "1,1,1"
expect_error "threads" "${o[@]}" --threads -2
[ -e "$out/o" ] && [ -n "$(ls -A "$out/o")" ] && { echo "FAIL: hyperbolicity-orbits output written despite errors"; fail=1; }

# Good runs write their data and manifests.
"$btob" hyperbolicity --r 0.3 --grid strip:8x4 --out "$out/h" --name ok --no-plot --quiet >/dev/null ||
  { echo "FAIL: a valid hyperbolicity run failed"; fail=1; }
"$btob" "${o[@]}" --name ok >/dev/null || { echo "FAIL: a valid hyperbolicity-orbits run failed"; fail=1; }
for f in "$out/h/ok.h5" "$out/h/ok.json" "$out/o/ok.h5" "$out/o/ok.json" "$out/o/ok_summary.csv"; do
  [ -s "$f" ] || { echo "FAIL: $f missing"; fail=1; }
done
[ -n "$(find "$out/h" "$out/o" -name "*tmp*")" ] && { echo "FAIL: temporary files left behind"; fail=1; }

# Float near the weak sink 312^150 (r = 0.171599, lambda1 = -0.0116): the orbit leaves it in float; both commands
# check float against double and warn; on the strong sink 1133 (r = 0.15) they stay quiet.
err=$("$btob" lyapunov --r 0.171599 --point 1,-3,-1.1 --iterations 100000 --precision float 2>&1 >/dev/null)
grep -q "warning: in double this orbit" <<<"$err" || { echo "FAIL: no float warning at r = 0.171599: $err"; fail=1; }
err=$("$btob" lyapunov --r 0.15 --point 1,-3,-1.1 --iterations 100000 --precision float 2>&1 >/dev/null)
[ -z "$err" ] || { echo "FAIL: float warning on the strong sink 1133: $err"; fail=1; }
err=$("$btob" lyapunov-map --r-min 0.171599 --r-max 0.171599 --r-count 1 --precision float --out "$out/f" --no-plot --quiet 2>&1)
grep -q "warning: float and double give another sign" <<<"$err" || { echo "FAIL: no lyapunov-map float warning: $err"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "cli_errors_lyapunov: all checks passed"; fi
exit $fail
