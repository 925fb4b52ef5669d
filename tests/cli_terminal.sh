#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# What the terminal says, run under a pseudo-terminal (script(1), bsdutils) so that progress bars
# are drawn as a user sees them:
#   - a progress bar ends its line: no "btob: ..." line starts after a bar on the same line;
#   - basins prints each attractor's fraction with its interval, and calls the points no attractor was found for
#     "undecided" (classify's word), never "unresolved";
#   - every command names the files it wrote, the PNG included.
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

tty_run() {  # tty_run <file for the transcript> <btob arguments...>: runs btob on a pseudo-terminal
  local log="$1"
  shift
  local cmd
  cmd=$(printf '%q ' "$btob" "$@")
  script -qec "$cmd" /dev/null >"$log" 2>&1 || { echo "FAIL: btob $* exited non-zero"; cat "$log"; fail=1; }
  tr -d '\r' <"$log" >"$log.lines"  # carriage returns redraw the bar; lines are what remains between newlines
}

expect_line() {  # expect_line <transcript> <extended regex> <what>
  if grep -Eq "$2" "$1.lines"; then echo "ok: $3"; else echo "FAIL: $3 (no line matching '$2')"; cat "$1.lines"; fail=1; fi
}

# A bar followed by the closing line on the same line looks like "...] 100% 0.6sbtob: ...".
no_bar_before_text() {
  if grep -Eq '%[ 0-9.]*sbtob:' "$1.lines"; then echo "FAIL: a line starts after a progress bar: $(grep -E '%[ 0-9.]*sbtob:' "$1.lines" | tail -c 120)"; fail=1
  else echo "ok: $2: no text after a progress bar on its line"; fi
}

tty_run "$out/basins.log" basins --r 0.21 --grid strip:200x200 --replicates 1 --out "$out/b"
no_bar_before_text "$out/basins.log" basins
expect_line "$out/basins.log" '^  [0-9]+ quasi-periodic P2 invariant curves: 0\.[0-9]+ \[0\.[0-9]+, 0\.[0-9]+\]$' \
  "basins prints each attractor's fraction and interval"
expect_line "$out/basins.log" '^  0 undecided: ' "basins prints the undecided fraction"
expect_line "$out/basins.log" ' attractors, undecided [0-9.]+ \([0-9]+ before refinement\)' \
  "basins' summary line gives the undecided fraction"
if grep -qi unresolved "$out/basins.log.lines"; then echo "FAIL: basins says 'unresolved'"; fail=1; else echo "ok: basins never says 'unresolved'"; fi
expect_line "$out/basins.log" "wrote .*basins_fractions\.csv.*basins\.h5.*basins\.png" "basins names its files, PNG included"

tty_run "$out/lmap.log" lyapunov-map --r-min 0.1 --r-max 0.2 --r-count 400 --iterations 2000 --out "$out/l"
no_bar_before_text "$out/lmap.log" lyapunov-map
expect_line "$out/lmap.log" "wrote .*lyapunov_map_summary\.csv.*lyapunov_map\.png" "lyapunov-map names its files, PNG included"

tty_run "$out/strip.log" strip-orbits --r 0.2 --orbits 3 --iterations 600 --tail 100 --out "$out/s"
for f in csv h5 json png; do
  expect_line "$out/strip.log" "wrote .*strip_orbits\.$f" "strip-orbits names its $f file"
done

tty_run "$out/particles.log" particles 1133 --r 0.15 --periods 20 --out "$out/p"
expect_line "$out/particles.log" "wrote .*particles\.csv.*spacetime\.png.*particles\.json" \
  "particles names its files, PNG included"

tty_run "$out/transfer.log" transfer --r 0.15 --boxes 16x16 --samples 4 --eigenvalues 4 --measure-orbits 2 \
  --measure-iterations 200 --tv-bins 8 --out "$out/t"
expect_line "$out/transfer.log" "wrote .*spectrum\.csv.*transfer\.h5.*transfer\.png" "transfer names its files, PNG included"

if [ "$fail" -eq 0 ]; then echo "cli_terminal: all checks passed"; fi
exit "$fail"
