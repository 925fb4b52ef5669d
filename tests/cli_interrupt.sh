#!/usr/bin/env bash
# Every command family stops on SIGINT and SIGTERM: exit 130 / 143, one line on stderr, nothing on stdout, no file
# written and an existing result in the output folder untouched, within a bound.  Each run would take minutes (or
# hours) to finish: a command that ignored the signal would fail the bound.  The bound is 2 s so that a loaded
# machine does not fail the test; the latency measured is printed (on an idle machine it is a few milliseconds, the
# cost of polling the token every core::cancel_stride steps).
# Usage: cli_interrupt.sh PATH/TO/btob
btob="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
bound=2.0   # seconds from the signal to the exit
settle=1.0  # seconds before the signal: past start-up and validation, inside the computation

# interrupt <INT|TERM> <btob arguments...>; "@OUT" in the arguments is replaced by an output folder that already
# holds a result (keep.txt), which must be left as it was.
interrupt() {
  local sig="$1"
  shift
  local out="$work/out" args=() a
  rm -rf "$out" && mkdir -p "$out" && echo "an earlier result" >"$out/keep.txt"
  for a in "$@"; do args+=("${a//@OUT/$out}"); done
  "$btob" "${args[@]}" >"$work/stdout" 2>"$work/stderr" &
  local pid=$!
  sleep "$settle"
  if ! kill -0 "$pid" 2>/dev/null; then
    wait "$pid"
    echo "FAIL (finished before the signal, exit $?): btob $*"; fail=1; return
  fi
  local t0 t1 rc
  t0=$(date +%s.%N)
  kill -"$sig" "$pid"
  for _ in $(seq 1 1000); do kill -0 "$pid" 2>/dev/null || break; sleep 0.005; done
  t1=$(date +%s.%N)
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "$pid"; wait "$pid" 2>/dev/null
    echo "FAIL (still running $(echo "$t1 - $t0" | bc) s after SIG$sig): btob $*"; fail=1; return
  fi
  wait "$pid"
  rc=$?
  local latency want lines files
  latency=$(echo "$t1 - $t0" | bc)
  want=$([ "$sig" = INT ] && echo 130 || echo 143)
  lines=$(grep -c . "$work/stderr")
  files=$(cd "$out" && ls -A | tr '\n' ' ')
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL (exit $rc, expected $want after SIG$sig): btob $*"; cat "$work/stderr"; fail=1
  elif [ "$lines" -ne 1 ] || ! grep -q "^btob: interrupted; nothing was written$" "$work/stderr"; then
    echo "FAIL ($lines lines on stderr, expected 'btob: interrupted; nothing was written'): btob $*"
    cat "$work/stderr"; fail=1
  elif [ -s "$work/stdout" ]; then
    echo "FAIL (wrote to stdout): btob $*"; head -3 "$work/stdout"; fail=1
  elif [ "$files" != "keep.txt " ] || [ "$(cat "$out/keep.txt")" != "an earlier result" ]; then
    echo "FAIL (output folder holds '$files'): btob $*"; fail=1
  elif (($(echo "$latency > $bound" | bc))); then
    echo "FAIL (exit $latency s after SIG$sig, bound $bound s): btob $*"; fail=1
  else
    echo "ok: SIG$sig -> exit $rc in $latency s: btob $*"
  fi
}

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
exit $fail
