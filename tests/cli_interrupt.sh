#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Every command family stops on SIGINT and SIGTERM: exit 130 / 143, one line on stderr, nothing on stdout, no file
# written and an existing result in the output folder untouched, within a bound.  Each run would take minutes (or
# hours) to finish: a command that ignored the signal would fail the bound.  The bound is 10 s, a margin that
# survives a machine loaded several times over; the latency measured is printed (on an idle machine it is a few
# milliseconds, the cost of polling the token every core::cancel_stride steps; benchmarks/bm_cancel.cpp measures it).
# Usage: cli_interrupt.sh PATH/TO/btob [MPIRUN]: with MPIRUN, sweeps under `mpirun -n 2` (with --resume) instead:
# the signal goes to every process of the job (as a batch system sends it) and the ranks must have ended within the
# bound, leaving the output folder as it was (with --resume: and the checkpoint of the finished items).  The ranks
# stop quietly (cli/mpi.cpp: the job is ending and said why; mpirun's exit status and messages are its own).
btob="$1"
mpirun="${2:-}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
bound=10.0  # seconds from the signal to the exit
settle=1.0  # seconds before the signal: past start-up and validation, inside the computation

# interrupt <INT|TERM> <btob arguments...>; "@OUT" in the arguments is replaced by an output folder that already
# holds a result (keep.txt), which must be left as it was.  With writing=1 (writing=1 interrupt ...) the signal comes
# 0.2 s after the run has begun to write its staged NAME.h5 (in OUT/.btob-tmp-*) instead of `settle` s after the start.
interrupt() {
  local sig="$1"
  shift
  local out="$work/out" args=() a
  rm -rf "$out" && mkdir -p "$out" && echo "an earlier result" >"$out/keep.txt"
  for a in "$@"; do args+=("${a//@OUT/$out}"); done
  "$btob" "${args[@]}" >"$work/stdout" 2>"$work/stderr" &
  local pid=$!
  if [ "${writing:-0}" = 1 ]; then
    for _ in $(seq 1 2000); do compgen -G "$out/.btob-tmp-*/*.h5" >/dev/null && break; sleep 0.005; done
    sleep 0.2
  else
    sleep "$settle"
  fi
  if ! kill -0 "$pid" 2>/dev/null; then
    wait "$pid"
    echo "FAIL (finished before the signal, exit $?): btob $*"; fail=1; return
  fi
  local t0 t1 rc
  t0=$(date +%s.%N)
  kill -"$sig" "$pid"
  for _ in $(seq 1 6000); do kill -0 "$pid" 2>/dev/null || break; sleep 0.005; done  # up to 30 s
  t1=$(date +%s.%N)
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "$pid"; wait "$pid" 2>/dev/null
    echo "FAIL (still running $(echo "$t1 - $t0" | bc) s after SIG$sig): btob $*"; fail=1; return
  fi
  wait "$pid"
  rc=$?
  local latency want lines files kept=0 want_files="keep.txt "
  latency=$(echo "$t1 - $t0" | bc)
  want=$([ "$sig" = INT ] && echo 130 || echo 143)
  # The estimate a run predicted over 10 minutes prints before it starts (a header line, then indented lines) is not
  # the interruption's: the rest of stderr must be its one line.
  lines=$(grep -v -E '^btob .*: (a long run; its estimate first|estimate before the run)|^  ' "$work/stderr" | grep -c .)
  files=$(cd "$out" && ls -A | tr '\n' ' ')
  # --resume: the finished items stay in OUT/NAME.checkpoint, and a line says so before the interruption's.
  if [[ " $* " == *" --resume "* ]]; then
    kept=1
    want_files=$(cd "$out" && ls -A | grep -x -e keep.txt -e '.*\.checkpoint\(\.[1-9][0-9]*\)\?' | tr '\n' ' ')
    grep -q "^btob: the finished items are kept in .*\.checkpoint; the same command with --resume continues$" \
      "$work/stderr" || kept=2
  fi
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL (exit $rc, expected $want after SIG$sig): btob $*"; cat "$work/stderr"; fail=1
  elif [ "$lines" -ne $((1 + kept)) ] || ! grep -q "^btob: interrupted; nothing was written$" "$work/stderr"; then
    echo "FAIL ($lines lines on stderr, expected 'btob: interrupted; nothing was written'): btob $*"
    cat "$work/stderr"; fail=1
  elif [ -s "$work/stdout" ]; then
    echo "FAIL (wrote to stdout): btob $*"; head -3 "$work/stdout"; fail=1
  elif [ "$files" != "$want_files" ] || [ "$(cat "$out/keep.txt")" != "an earlier result" ]; then
    echo "FAIL (output folder holds '$files'): btob $*"; fail=1
  elif (($(echo "$latency > $bound" | bc))); then
    echo "FAIL (exit $latency s after SIG$sig, bound $bound s): btob $*"; fail=1
  else
    echo "ok: SIG$sig -> exit $rc in $latency s: btob $*"
  fi
}

# interrupt_mpi <INT|TERM> <btob arguments...>: the job's every process gets the signal; its ranks must be gone
# within the bound and the folder (@OUT) hold keep.txt and, with --resume, the checkpoint (a file per rank) alone.
interrupt_mpi() {
  local sig="$1"
  shift
  local out="$work/out" args=() a
  rm -rf "$out" && mkdir -p "$out" && echo "an earlier result" >"$out/keep.txt"
  for a in "$@"; do args+=("${a//@OUT/$out}"); done
  setsid "$mpirun" -n 2 "$btob" "${args[@]}" >"$work/stdout" 2>"$work/stderr" &
  local pid=$!
  sleep "$settle"
  local ranks
  ranks=$(pgrep -s "$pid" -x btob | tr '\n' ' ')
  if [ -z "$ranks" ]; then
    wait "$pid"
    echo "FAIL (no rank running before the signal, exit $?): mpirun -n 2 btob $*"; cat "$work/stderr"; fail=1; return
  fi
  local t0 t1 r alive
  t0=$(date +%s.%N)
  pkill -"$sig" -s "$pid"
  for _ in $(seq 1 6000); do  # up to 30 s
    alive=0
    # A rank that has ended is a zombie until mpirun reaps it (its own shutdown takes a second): not running.
    for r in $ranks; do [[ "$(ps -o stat= -p "$r" 2>/dev/null)" == [^Z]* ]] && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.005
  done
  t1=$(date +%s.%N)
  if [ $alive = 1 ]; then
    pkill -KILL -s "$pid"; wait "$pid" 2>/dev/null
    echo "FAIL (ranks still running $(echo "$t1 - $t0" | bc) s after SIG$sig): mpirun -n 2 btob $*"; fail=1; return
  fi
  wait "$pid" 2>/dev/null
  local latency files want="keep.txt "
  latency=$(echo "$t1 - $t0" | bc)
  # With --resume: each rank's checkpoint (OUT/NAME.checkpoint, OUT/NAME.checkpoint.K).
  [[ " $* " == *" --resume "* ]] &&
    want=$(cd "$out" && ls -A | grep -x -e keep.txt -e '.*\.checkpoint\(\.[1-9][0-9]*\)\?' | tr '\n' ' ')
  files=$(cd "$out" && ls -A | tr '\n' ' ')
  if [ "$files" != "$want" ] || [ "$(cat "$out/keep.txt")" != "an earlier result" ]; then
    echo "FAIL (output folder holds '$files'): mpirun -n 2 btob $*"; fail=1
  elif (($(echo "$latency > $bound" | bc))); then
    echo "FAIL (ranks ended $latency s after SIG$sig, bound $bound s): mpirun -n 2 btob $*"; fail=1
  else
    echo "ok: SIG$sig -> ranks ended in $latency s: mpirun -n 2 btob $*"
  fi
}

if [ -n "$mpirun" ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  export OMPI_MCA_btl_base_warn_component_unused=0
  # Items that are long orbits (polled inside a batch), the atlas's enumeration of its words (counted before the
  # split), covariant vectors (a transient of 1e12 steps); with --resume the items run in rounds.
  interrupt_mpi TERM lyapunov-map --r-count 4 --iterations 100000000000 --grid 1,-0.5,-1.1 --threads 1 --out @OUT --no-plot --resume
  interrupt_mpi TERM pattern atlas --max-length 16 --no-check --threads 1 --out @OUT --no-plot
  interrupt_mpi INT pattern atlas --max-length 16 --no-check --threads 1 --out @OUT --no-plot --resume
  interrupt_mpi TERM hyperbolicity-orbits --r-count 4 --iterations 1000 --transient 1000000000000 --grid 1,-0.5,-1.1 --threads 1 --out @OUT --no-plot --resume
  exit $fail
fi

orbit=(--r 0.2 --point 1,-0.5,-1.1)
# Single orbits in the kernel's and the scalar routes' precisions (MPFR included), transients.
interrupt INT lyapunov "${orbit[@]}" --iterations 1000000000000
interrupt TERM lyapunov "${orbit[@]}" --iterations 1000000000000
interrupt TERM lyapunov "${orbit[@]}" --iterations 1000000000 --precision mpfr:40
interrupt INT classify "${orbit[@]}" --transient 1000000000000
# Sweeps whose every item is one long orbit (a batch is polled inside, not only between batches).
interrupt TERM bifurcation --r-count 2 --iterations 100000000000 --tail 100 --grid 1,-0.5,-1.1 --out @OUT --no-plot
interrupt INT bifurcation --r-count 2 --iterations 100000000 --tail 100 --grid 1,-0.5,-1.1 --precision mpfr:30 --out @OUT --no-plot
interrupt TERM bifurcation --algorithm trig --r-count 2 --iterations 100000000 --tail 100 --grid 1,-0.5,-1.1 --out @OUT --no-plot
interrupt TERM lyapunov-map --r-count 2 --iterations 100000000000 --grid 1,-0.5,-1.1 --out @OUT --no-plot
# The atlas (words), windows and their certificates (one n of exact arithmetic), transfer (matrix, Arnoldi), particles.
interrupt INT pattern atlas --max-length 12 --out @OUT --no-plot
# Inside the enumeration of the words (3^16 of length 16 alone: seconds before the first word is analysed).
interrupt TERM pattern atlas --max-length 16 --no-check --out @OUT --no-plot
interrupt TERM windows bounds --n 1000 --certify
interrupt INT transfer --r 0.3 --boxes 1024x1024 --out @OUT --no-plot
interrupt TERM particles 1133 --r 0.15 --periods 100000000 --precision mpfr:40 --out @OUT --no-plot
# The other families, each in a loop that ran for seconds to minutes unpolled before: a long double orbit, the
# correlation's transient and its direct sum over lags, strip orbits and their classification, the pattern curves'
# r values, the precision study, transfer's dense eigensolver (one block of 576 boxes, solved on a thread of its own)
# and its scan over r, windows' polynomials, iterator checks and precision study, the covariant vectors' transient,
# and the sweeps over grids.
interrupt TERM lyapunov "${orbit[@]}" --iterations 1000000000000 --precision long-double
interrupt INT correlate "${orbit[@]}" --transient 1000000000000 --iterations 1000 --n-max 10 --fit-lags 10 --out @OUT --no-plot
interrupt TERM correlate "${orbit[@]}" --iterations 2000000 --n-max 200000 --method direct --out @OUT --no-plot
interrupt TERM strip-orbits --orbits 1000 --iterations 10000000 --tail 100 --out @OUT --no-plot
interrupt INT particles 1133 --r 0.15 --periods 100000000 --out @OUT --no-plot
interrupt TERM pattern-curves --word "132^200" --r-count 60000 --out @OUT --no-plot
interrupt TERM precision --orbits 2000 --iterations 100000 --out @OUT --no-plot
interrupt TERM transfer --r 0.3 --boxes 24x24 --tv-bins 8 --samples 4096 --out @OUT --no-plot
interrupt INT transfer-r --r-count 1000 --boxes 256x256 --out @OUT --no-plot
interrupt TERM windows poly --n 1..3000 --out @OUT
interrupt TERM windows verify --n 2..3 --iterations 100000000000 --out @OUT
interrupt INT windows precision --n 1..2000 --out @OUT --no-plot
interrupt TERM hyperbolicity-orbits --r-count 4 --iterations 1000 --transient 1000000000000 --grid 1,-0.5,-1.1 --out @OUT --no-plot
interrupt TERM lyapunov-strip --grid strip:2x1 --iterations 100000000000 --out @OUT --no-plot
interrupt INT basins --r 0.2 --grid strip:2x2 --replicates 0 --transient 100000000000 --out @OUT --no-plot
interrupt TERM basins-r --r-values 0.2 --grid 1,-0.5,-1.1 --transient 100000000000 --out @OUT --no-plot
interrupt TERM hyperbolicity --r 0.2 --grid strip:3000x3000 --out @OUT --no-plot
interrupt TERM measure --r 0.2 --grid 1,-0.5,-1.1 --transient 100000000000 --iterations 1000 --out @OUT --no-plot
# With --resume: the atlas's words are counted (3^16 of them) before the first round.
interrupt TERM pattern atlas --max-length 16 --no-check --out @OUT --no-plot --resume
# A word's analysis in MPFR (a primitive word of 59995 symbols at 2000 digits: a minute) and its stability set in
# MPFR (7500 r values and their bisections for 1801 symbols: minutes).
interrupt INT pattern "(132312)^9999 1" --r 0.2 --precision mpfr:2000
interrupt TERM pattern "(132312)^300 1" --window --precision mpfr:100
# Inside the deflated write of two 48 MB datasets (chaotic tails compress little: an 89 MB NAME.h5, seconds to
# write), which is written one chunk at a time.
writing=1 interrupt TERM strip-orbits --r 0.9 --orbits 1000 --iterations 6000 --tail 6000 --threads 1 --out @OUT --no-plot

# Killed outright (SIGKILL: no handler runs) while writing, a run leaves its staging folder; the next run of the same
# result into the same folder removes it (its process no longer runs on this host) and leaves alone a folder of a
# process that still runs (this shell's, made up here) and one of another host.
killed_outright() {
  local out="$work/killed" host live other stale files
  rm -rf "$out" && mkdir -p "$out"
  "$btob" strip-orbits --r 0.9 --orbits 1000 --iterations 6000 --tail 6000 --threads 1 --out "$out" --name so \
    --no-plot >/dev/null 2>&1 &
  local pid=$!
  for _ in $(seq 1 4000); do compgen -G "$out/.btob-tmp-*/*.h5" >/dev/null && break; sleep 0.005; done
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  stale=$(cd "$out" && ls -A | grep '^\.btob-tmp-' | tr '\n' ' ')
  host=$(hostname | tr - _)
  live=".btob-tmp-so-$host-$$-0"
  other=".btob-tmp-so-another_host-$pid-0"
  mkdir "$out/$live" "$out/$other"
  "$btob" strip-orbits --r 0.9 --orbits 10 --iterations 100 --tail 10 --out "$out" --name so --no-plot --quiet
  files=$(cd "$out" && ls -A | grep -v '^so[._]' | sort | tr '\n' ' ')
  if [ -z "$stale" ]; then
    echo "FAIL (SIGKILL while writing left no staging folder to clean: the check tests nothing)"; fail=1
  elif [ "$files" != "$(printf '%s\n' "$other" "$live" | sort | tr '\n' ' ')" ] || [ ! -e "$out/so.h5" ]; then
    echo "FAIL (after a run killed outright and the next run, the folder holds '$files'; killed: '$stale')"; fail=1
  else
    echo "ok: SIGKILL left '$stale'; the next run removed it and kept a live process's and another host's"
  fi
}
killed_outright
exit $fail
