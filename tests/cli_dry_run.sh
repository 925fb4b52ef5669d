#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# --dry-run (core/estimate.hpp): the predicted time of three sweeps of different kinds (r values with long orbits,
# grid rows of a basin image, n values of certified window bounds) lies within a factor of 2 of the measured run
# time, and a dry run writes nothing.  The same for three requests that are not sweeps, priced by the cached route
# rates (core/work.hpp, io/rates.hpp): one orbit's derivative cocycle, the classifier's two passes, the particles'
# event loop, each from a cold cache and the first again from a warm one; a corrupt, a foreign and an unwritable
# cache are recalibrated without an error; a sweep of about half an hour prints its estimate before it starts, a
# short one does not.  Timing on a shared machine: a command outside the factor is measured
# once more (dry run and run again, back to back) before the test fails.
#
# Usage: cli_dry_run.sh BTOB [sweeps|plans|counted|cache|sized]   (default: all five parts; CTest runs them as separate
# tests; the sweeps, counted and sized parts, which run the requests too, are left out of the unoptimised sanitizer
# build, where each run takes ten to a hundred times longer: it runs the sweeps' dry runs alone, the plans part)
set -u
BTOB=$1
PART=${2:-all}
TMP=$(mktemp -d)
# The rate cache of this test alone, outside the folder whose emptiness shows that a dry run wrote nothing.
export XDG_CACHE_HOME
XDG_CACHE_HOME=$(mktemp -d)
RATES=$XDG_CACHE_HOME/btob/rates.json
trap 'rm -rf "$TMP" "$XDG_CACHE_HOME"' EXIT
cd "$TMP" || exit 1
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# predict NAME ARGS...: the dry run's predicted seconds into $predicted (empty, and a failure, when it printed none);
# the dry run must write nothing.
predict() {
  local name=$1
  shift
  predicted=$("$BTOB" "$@" --threads 1 --quiet --dry-run --out dry | sed -n 's/^  predicted: \([0-9.e+-]*\) s.*/\1/p')
  [ -n "$predicted" ] || fail "$name: no prediction"
  [ ! -e dry ] && [ -z "$(ls)" ] || fail "$name: the dry run wrote $(ls)"
}

# within NAME ARGS...: 0 when the dry run's prediction is within a factor 2 of the run's wall time (printed).
within() {
  local name=$1
  local t0 t1 actual
  predict "$@"
  [ -n "$predicted" ] || return 0
  shift
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

# The three sweeps: r values with long orbits, grid rows of a basin image, n values of certified window bounds.
bif=(bifurcation --r-min 0.08 --r-max 0.4 --r-count 100 --iterations 1000000 --tail 40 --bins 200 --raw --no-plot)
bas=(basins --r 0.11 --grid strip:200x200 --replicates 1 --transient 20000 --iterations 3000 --max-period 200
     --lyap-iterations 400 --refine-factor 2 --no-plot)
win=(windows bounds --n 1..80 --certify --digits 15)

# plan NAME ARGS...: the dry run alone prints a prediction and writes nothing.
plan() {
  predict "$@"
  [ -z "$predicted" ] || echo "$1: predicted $predicted s (the dry run alone)"
}

if [ "$PART" = all ] || [ "$PART" = sweeps ]; then
check bifurcation "${bif[@]}"
check basins "${bas[@]}"
check windows-bounds "${win[@]}"
fi

# The sweeps' dry runs alone: the part the sanitizer build runs (each of its runs takes minutes there; the comparison
# with the run is the sweeps part's).
if [ "$PART" = all ] || [ "$PART" = plans ]; then
plan bifurcation "${bif[@]}"
plan basins "${bas[@]}"
plan windows-bounds "${win[@]}"
# A request whose items come from a data file (basins-r --table: Table 6.1's r values) is sampled on them.
"$BTOB" basins-r --table --grid random:20 --threads 1 --dry-run > table.txt 2>&1 || fail "basins-r --table --dry-run: $(cat table.txt)"
grep -q "^  work: 33 items" table.txt || fail "basins-r --table's dry run did not see Table 6.1's 33 r values: $(cat table.txt)"
grep -qi "nan" table.txt && fail "basins-r --table's dry run printed NaN: $(cat table.txt)"
rm -f table.txt
fi

# Requests that are not sweeps, each from a cold cache (its routes calibrated by their probes), and the first again
# from the warm cache it left.
if [ "$PART" = all ] || [ "$PART" = counted ]; then
rm -rf "$XDG_CACHE_HOME/btob"
# 5e7 steps: about 0.5 s of the one-orbit route in double, well above the process's start (~0.05 s)
check lyapunov lyapunov --r 0.2 --point 1,-0.5,-1.1 --iterations 50000000 --transient 1000
grep -q '"format": "btob route rates 1"' "$RATES" || fail "no rate cache written to $RATES"
"$BTOB" lyapunov --r 0.2 --point 1,-0.5,-1.1 --threads 1 --dry-run > warm.txt || fail "lyapunov dry run failed"
grep -q "cached from" warm.txt || fail "a second dry run did not read the cached rate: $(cat warm.txt)"
rm -f warm.txt
check lyapunov-warm lyapunov --r 0.2 --point 1,-0.5,-1.1 --iterations 50000000 --transient 1000
rm -rf "$XDG_CACHE_HOME/btob"
check classify classify --r 0.2 --point 1,-0.5,-1.1 --transient 30000000 --lyap-iterations 3000000 --refine-factor 0
rm -rf "$XDG_CACHE_HOME/btob"
# The particles in MPFR: the event loop dominates.  In double, writing NAME.h5's three ratios per period (deflated,
# at a speed that depends on how the data compress) is a third of a run of this length, which no route prices.
check particles particles 1133 --r 0.15 --periods 60000 --precision mpfr:40 --no-plot
# A sweep predicted over 10 minutes says so before it starts (the sample runs only when its map steps may take a
# minute): the note within a few seconds of the start, then SIGINT; a short sweep prints no note.
"$BTOB" bifurcation --r-count 1000000 --iterations 100000 --grid random:64 --bins 10 --threads 2 --no-plot --out big \
  2> note.txt &
pid=$!
for _ in $(seq 300); do grep -q "estimate before the run" note.txt 2> /dev/null && break; sleep 0.1; done  # 30 s
kill -INT $pid 2> /dev/null
wait $pid
grep -q "estimate before the run" note.txt || fail "a sweep of ~30 min printed no estimate before it started: $(cat note.txt)"
grep -q "predicted: " note.txt || fail "the note before the run has no prediction: $(cat note.txt)"
[ ! -e big ] || fail "the interrupted sweep wrote big/"
"$BTOB" bifurcation --r-count 20 --iterations 1000 --no-plot --out small 2> note.txt
grep -q "estimate before the run" note.txt && fail "a short sweep printed an estimate: $(cat note.txt)"
rm -rf small note.txt
fi

# Requests whose cost grows steeply with one size (a window bound's n, a word's length, the digits): the dry run fits
# a cost model on small instances (core/size_model.hpp) and never runs the request itself.  Each dry run finishes
# within 10 s of wall time (a loose bound for a loaded machine; the fit's budget is about a second, where the
# request's own sample ran 235 s for --n 2000), says when it extrapolates, and predicts the run within a factor 3
# (or 0.3 s, for a run so short that process start-up is a good part of it).  The runs take a few seconds.
if [ "$PART" = all ] || [ "$PART" = sized ]; then
# sized NAME ARGS...: the three checks above, once more (dry run and run) before failing on the factor.
sized_within() {
  local name=$1
  shift
  local t0 t1 dry predicted actual
  t0=$(date +%s.%N)
  dry=$("$BTOB" "$@" --threads 1 --dry-run 2>&1) || { fail "$name: the dry run failed: $dry"; return 0; }
  t1=$(date +%s.%N)
  echo "$(echo "$t1 - $t0" | bc -l) < 10" | bc -l | grep -qx 1 || { fail "$name: the dry run took $(echo "$t1 - $t0" | bc -l) s"; return 0; }
  grep -q "extrapolated from sizes\|interpolated from sizes" <<< "$dry" || { fail "$name: no cost model in: $dry"; return 0; }
  predicted=$(sed -n 's/^  predicted: \([0-9.e+-]*\) s.*/\1/p' <<< "$dry")
  [ -n "$predicted" ] || { fail "$name: no prediction: $dry"; return 0; }
  t0=$(date +%s.%N)
  "$BTOB" "$@" --threads 1 > /dev/null 2>&1 || { fail "$name: the run failed"; return 0; }
  t1=$(date +%s.%N)
  actual=$(echo "$t1 - $t0" | bc -l)
  echo "$name: predicted $predicted s ($(grep -o 'extrapolated from sizes [0-9.]*\|interpolated from sizes [0-9.]*' <<< "$dry")), measured $actual s"
  echo "($predicted <= 3 * $actual && $actual <= 3 * $predicted) || ($predicted - $actual)^2 < 0.09" | bc -l | grep -qx 1
}
sized() {
  sized_within "$@" || sized_within "$@" || fail "$1: the prediction is not within a factor 3 of the run, twice"
}
sized windows-bounds-300 windows bounds --n 300 --certify
# Beyond what fits in the fit's budget the dry run says it extrapolates.  n = 2000: the instances stop near 256 on any
# machine (n = 300 itself fits the budget on an idle one, where the fit times it and rightly says "interpolated").
grep -q "extrapolated from sizes" <<< "$("$BTOB" windows bounds --n 2000 --certify --dry-run)" ||
  fail "windows bounds --n 2000: the dry run does not say that it extrapolates"
# A random word of 3000 symbols (seeded) in MPFR, whose verdict walks the orbit of every eigenvalue.
word=$(python3 -c "import random; random.seed(7); print(''.join(random.choice('123') for _ in range(3000)))")
sized pattern-3000-mpfr pattern "$word" --r 0.5 --precision mpfr:60
# Periodic words: their prefixes' orbit walks converge in few or many periods (0.1 to 2.5 ms a symbol in mpfr:60),
# so a power law in the length through two of them predicted 4e3 to 1e4 s for a run of 2-4 s (float128: 4.6e5 s,
# long double 8.9e5 s); the model in the counted work (patterns/cost.cpp) prices them.
sized pattern-periodic-mpfr pattern "(132312)^500 1" --r 0.2 --precision mpfr:60
sized pattern-periodic-float128 pattern "(132312)^500 1" --r 0.2 --precision float128
sized pattern-periodic-long-double pattern "(132312)^2000 1" --r 0.2 --precision long-double
sized thresholds windows thresholds --digits 10000
fi

# A corrupt and a foreign cache file are recalibrated over (and rewritten in the cache's format); an unwritable
# cache directory means no cache, not an error.
if [ "$PART" = all ] || [ "$PART" = cache ]; then
mkdir -p "$XDG_CACHE_HOME/btob"
for content in '{"format": "btob route rates 1", "rates": {"x": ' '{"some": "other program"}'; do
  printf '%s' "$content" > "$RATES"
  "$BTOB" lyapunov --r 0.2 --point 1,-0.5,-1.1 --threads 1 --dry-run > out.txt 2>&1 || fail "cache '$content': $(cat out.txt)"
  grep -q "calibrated now" out.txt || fail "cache '$content' was read: $(cat out.txt)"
  python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['format'] == 'btob route rates 1'" "$RATES" ||
    fail "cache '$content' was not rewritten"
  rm -f out.txt
done
XDG_CACHE_HOME=/proc/btob-no-such-dir "$BTOB" lyapunov --r 0.2 --point 1,-0.5,-1.1 --dry-run > out.txt 2>&1 ||
  fail "an unwritable cache is an error: $(cat out.txt)"
grep -q "^  predicted: " out.txt || fail "no prediction without a cache: $(cat out.txt)"
rm -f out.txt
# A request that is its own probe (a word's window) keeps the time of a completed run: the dry run after it reads
# the cache instead of running it again.
"$BTOB" pattern 1133 --window > /dev/null || fail "pattern 1133 --window failed"
"$BTOB" pattern 1133 --window --dry-run > out.txt 2>&1 || fail "pattern --dry-run: $(cat out.txt)"
grep -q "cached from" out.txt || fail "a completed run of a self-probed request left no rate: $(cat out.txt)"
rm -f out.txt
fi
[ -z "$(ls)" ] || fail "the dry runs left $(ls)"

[ $failures -eq 0 ] && echo "dry run ($PART): all checks passed" && exit 0
exit 1
