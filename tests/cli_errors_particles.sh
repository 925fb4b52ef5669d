#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The error contract of `btob particles`, as tests/cli_errors.sh checks it for the others: bad input gets
# a one-line error naming the field, exit status 2, and no output file written.
# Usage: cli_errors_particles.sh PATH/TO/btob
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

p=(particles --out "$out/p" --no-plot --periods 10)
expect_error "word" "${p[@]}" 1113 --r 0.3          # 1113 is feasible (unstable) only below r = 0.0864
expect_error "word" "${p[@]}" 12 --r 0.3             # 12 is feasible only below 3 - 2 sqrt(2)
expect_error "word" "${p[@]}" 14 --r 0.15            # not a word over 1, 2, 3
expect_error "r" "${p[@]}" 1133 --r 1.5
expect_error "r" "${p[@]}" 1133 --r 0
expect_error "r" "${p[@]}" 1133 --r nan
expect_error "periods" particles --out "$out/p" --no-plot 1133 --r 0.15 --periods 0
expect_error "periods" particles --out "$out/p" --no-plot 1133 --r 0.15 --periods -3
expect_error "precision" "${p[@]}" 1133 --r 0.15 --precision float
expect_error "precision" "${p[@]}" 1133 --r 0.15 --precision mpfr:3
expect_error "start" "${p[@]}" 1133 --r 0.15 --start sideways
expect_error "diagram-periods" "${p[@]}" 1133 --r 0.15 --diagram-periods 0
[ -e "$out/p" ] && { echo "FAIL: refused particles runs wrote $out/p: $(ls -A "$out/p")"; fail=1; }

# A valid small run prints one CSV row and writes its files, no temporaries.
row=$("$btob" "${p[@]}" 1133 --r 0.15 2>/dev/null)
[ "$(printf '%s\n' "$row" | grep -c .)" -eq 1 ] || { echo "FAIL: expected one CSV row, got: $row"; fail=1; }
case "$row" in 1133,0.15,10,*,true,*) ;; *) echo "FAIL: unexpected row: $row"; fail=1 ;; esac
for f in particles.csv convergence.csv events.csv particles.json; do
  [ -s "$out/p/$f" ] || { echo "FAIL: $out/p/$f missing"; fail=1; }
done
[ -n "$(find "$out/p" -name "*tmp*")" ] && { echo "FAIL: temporary files left behind"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "cli_errors_particles: all checks passed"; fi
exit $fail
