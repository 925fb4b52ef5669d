#!/bin/bash
# --dry-run (src/cli/estimate.hpp): the predicted time of three sweeps of different kinds (r values with long orbits,
# grid rows of a basin image, n values of certified window bounds) lies within a factor of 2 of the measured run
# time, and a dry run writes nothing.  Timing on a shared machine: a command outside the factor is measured once
# more (dry run and run again, back to back) before the test fails.
#
# Usage: cli_dry_run.sh BTOB
set -u
BTOB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# within NAME ARGS...: 0 when the dry run's prediction is within a factor 2 of the run's wall time (printed).
within() {
  local name=$1
  shift
  local predicted t0 t1 actual
  predicted=$("$BTOB" "$@" --threads 1 --quiet --dry-run --out dry | sed -n 's/^  predicted: \([0-9.e+-]*\) s.*/\1/p')
  [ -n "$predicted" ] || { fail "$name: no prediction"; return 0; }
  [ ! -e dry ] && [ -z "$(ls)" ] || fail "$name: the dry run wrote $(ls)"
  t0=$(date +%s.%N)
  "$BTOB" "$@" --threads 1 --quiet --out run > /dev/null || { fail "$name: the run failed"; return 0; }
  t1=$(date +%s.%N)
  rm -rf run
  actual=$(echo "$t1 - $t0" | bc -l)
  echo "$name: predicted $predicted s, measured $actual s"
  echo "$predicted <= 2 * $actual && $actual <= 2 * $predicted" | bc -l | grep -qx 1
}

check() {
  within "$@" || within "$@" || fail "$1: the prediction is not within a factor 2 of the run, twice"
}

check bifurcation bifurcation --r-min 0.08 --r-max 0.4 --r-count 100 --iterations 1000000 --tail 40 --bins 200 \
  --raw --no-plot
check basins basins --r 0.11 --grid strip:200x200 --replicates 1 --transient 20000 --iterations 3000 \
  --max-period 200 --lyap-iterations 400 --refine-factor 2 --no-plot
check windows-bounds windows bounds --n 1..80 --certify --digits 15

[ $failures -eq 0 ] && echo "dry run: predictions within a factor 2" && exit 0
exit 1
