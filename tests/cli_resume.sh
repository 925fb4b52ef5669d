#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# --resume (src/cli/checkpoint.hpp): a sweep killed with SIGKILL at a random point after its checkpoint holds
# finished parts, resumed (killed and resumed once more), writes the uninterrupted run's data bitwise (HDF5 datasets
# through tests/h5_same_data.py, CSV files and standard output byte for byte) and removes its checkpoint; a resume
# with another request is refused with one line naming the field, exit 2.
#
# Usage: cli_resume.sh BTOB [MPIRUN]: with MPIRUN, the killed and resumed runs are `mpirun -n 2` jobs (the whole job
# killed, as a node failure or a batch system would), the reference a single process; then a job of 3 ranks killed
# and resumed by jobs of 2 ranks (its rows written by the ranks, items no longer in a cyclic split), and one of 2
# resumed by 3 gathering to rank 0 (BTOB_MPI_WRITE=gather), each rank's file holding its own share alone
# (tests/checkpoint_items.py).
set -u
BTOB=$1
MPIRUN=${2:-}
HERE=$(cd "$(dirname "$0")" && pwd)
PY=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_base_warn_component_unused=0 OMPI_MCA_orte_base_help_aggregate=1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
launch=("$BTOB")
[ -n "$MPIRUN" ] && launch=("$MPIRUN" -n 2 "$BTOB")

# kill_after_checkpoint FILE ARGS...: starts the run in its own session, waits until FILE has grown past its
# first size (a part appended), waits 0..0.3 s more, kills its whole session with SIGKILL.  Prints "killed" or "ended".
kill_after_checkpoint() {
  local file=$1
  shift
  setsid "${launch[@]}" "$@" > /dev/null 2>&1 &
  local pid=$! s0=
  for _ in $(seq 600); do  # at most 30 s
    kill -0 $pid 2> /dev/null || break
    if [ -e "$file" ]; then
      local s
      s=$(stat -c %s "$file")
      [ -z "$s0" ] && s0=$s
      [ "$s" -gt "$s0" ] && break
    fi
    sleep 0.05
  done
  sleep "0.$((RANDOM % 4))"
  if kill -0 $pid 2> /dev/null; then
    # Every process of the session: mpirun's ranks may have left its process group (a lost node loses them all).
    pkill -KILL -s $pid 2> /dev/null
    wait $pid 2> /dev/null
    for _ in $(seq 100); do pgrep -s $pid > /dev/null || break; sleep 0.05; done
    echo killed
  else
    wait $pid 2> /dev/null
    echo ended
  fi
}

# resumed NAME CHECKPOINT ARGS...: the uninterrupted run, then the same run killed twice and resumed.  CHECKPOINT is
# OUT/x.checkpoint for a command writing files (OUT: ref/ and res/), ./x.checkpoint for one printing its result.
resumed() {
  local name=$1 cp=$2
  shift 2
  mkdir -p "$name/ref" "$name/res" && cd "$name" || return
  local common=(--threads 1 --quiet --name x) first second
  local out=()  # each run works in its own folder (ref/, res/): a command writing files writes there
  [ "$cp" = OUT/x.checkpoint ] && out=(--out .)
  cp=res/x.checkpoint
  if ! (cd ref && "$BTOB" "$@" "${common[@]}" "${out[@]}" > ../ref.stdout); then
    fail "$name: the uninterrupted run failed"
    cd .. && return
  fi
  first=$(cd res && kill_after_checkpoint x.checkpoint "$@" "${common[@]}" "${out[@]}" --resume)
  [ "$first" = killed ] && [ -e "$cp" ] || fail "$name: not killed with a checkpoint ($first)"
  second=$(cd res && kill_after_checkpoint x.checkpoint "$@" "${common[@]}" "${out[@]}" --resume)
  if ! (cd res && "${launch[@]}" "$@" "${common[@]}" "${out[@]}" --resume > ../res.stdout); then
    fail "$name: the resumed run failed"
    cd .. && return
  fi
  [ ! -e "$cp" ] || fail "$name: the checkpoint is left after the result was written"
  if [ -e ref/x.h5 ]; then
    "$PY" "$HERE/h5_same_data.py" ref/x.h5 res/x.h5 > cmp.txt || fail "$name: $(cat cmp.txt)"
  fi
  for f in ref/*.csv; do
    [ -e "$f" ] || continue
    cmp -s "$f" "res/$(basename "$f")" || fail "$name: $(basename "$f") differs"
  done
  cmp -s ref.stdout res.stdout || fail "$name: another standard output"
  echo "ok: $name killed ($first, then $second) and resumed: the uninterrupted run's data"
  cd ..
}

# Under mpirun: three kinds (r values: across below, grid rows, n values) and the refusal, to keep the job starts few.
mpi_skip() { [ -n "$MPIRUN" ]; }
mpi_skip || resumed bifurcation OUT/x.checkpoint bifurcation --r-min 0.08 --r-max 0.4 --r-count 200 \
  --iterations 1000000 --tail 40 --bins 200 --raw --no-plot
mpi_skip || resumed lyapunov-map OUT/x.checkpoint lyapunov-map --r-min 0.08 --r-max 0.3 --r-count 100 --iterations 500000 \
  --transient 200 --blocks 5 --no-plot
resumed basins OUT/x.checkpoint basins --r 0.11 --grid strip:200x200 --replicates 1 --transient 20000 \
  --iterations 3000 --max-period 200 --lyap-iterations 400 --refine-factor 2 --no-plot
mpi_skip || resumed basins-r OUT/x.checkpoint basins-r --r-values 0.11 0.13 0.15 0.17 0.2 0.22 0.25 0.27 --grid random:20000 \
  --boundary-grid sphere:40x40 --transient 5000 --iterations 3000 --max-period 200 --lyap-iterations 400 --refine-factor 2 --no-plot
mpi_skip || resumed pattern-atlas OUT/x.checkpoint pattern atlas --max-length 7 --ics 100 --iterations 2000 --tail 500 \
  --max-period 200 --no-plot
# A command that prints its result (Table B.1 with certificates): the checkpoint is ./NAME.checkpoint.
resumed windows-bounds ./x.checkpoint windows bounds --n 1..100 --certify --digits 15

# Another request on a checkpoint: refused, one line naming the field, exit 2, the checkpoint kept.
args=(bifurcation --r-min 0.08 --r-max 0.4 --r-count 200 --iterations 1000000 --tail 40 --threads 1 --quiet --no-plot)
state=$(kill_after_checkpoint other/bifurcation.checkpoint "${args[@]}" --out other --resume)
kept=$(cd other && stat -c '%n %s' ./*)
"${launch[@]}" "${args[@]/200/201}" --out other --resume > out.txt 2> err.txt
code=$?
[ $code -eq 2 ] || fail "another request: exit $code, expected 2 ($state)"
[ "$(grep -c '^btob' err.txt)" = 1 ] && grep -q "^btob: error: other/bifurcation.checkpoint: a checkpoint of another \
request or build (r-count: '200' there, '201' here)" err.txt || fail "another request: $(cat err.txt)"
[ -e other/bifurcation.checkpoint ] && [ "$(cd other && stat -c '%n %s' ./*)" = "$kept" ] ||
  fail "another request: files changed ($(ls other))"

# Under mpirun each rank keeps its own parts in its own file (OUT/x.checkpoint, OUT/x.checkpoint.K), and a job may
# resume with another number of ranks.  across P1 P2 P3 [ENV...]: a bifurcation (rows the ranks write) killed as a
# job of P1 ranks (each file then holds its rank's share of items and no more: tests/checkpoint_items.py), resumed
# and killed as a job of P2 (P2 = -: not run; every item still in one file only: the earlier files were read, not
# recomputed), resumed to the end by P3 ranks; the data equal the uninterrupted run's bitwise and every file is
# removed.  (A single process reading a job's files: tests/test_checkpoint.cpp.)
across() {
  local p1=$1 p2=$2 p3=$3 dir="across_$1_$2_$3" state= before=$failures
  shift 3
  local args=(bifurcation --r-min 0.08 --r-max 0.4 --r-count 200 --iterations 1000000 --tail 40 --bins 200 --raw
    --no-plot --threads 1 --quiet --name x --out . --resume)
  mkdir -p "$dir" && cd "$dir" || return
  launch=(env "$@" "$MPIRUN" -n "$p1" "$BTOB")
  state=$(kill_after_checkpoint x.checkpoint "${args[@]}")
  [ "$state" = killed ] || fail "$dir: not killed ($state)"
  shopt -s nullglob
  local files=(x.checkpoint*)
  "$PY" "$HERE/checkpoint_items.py" share "$p1" 200 "${files[@]}" > share.txt || fail "$dir: $(cat share.txt)"
  if [ "$p2" != - ]; then
    launch=(env "$@" "$MPIRUN" -n "$p2" "$BTOB")
    state=$(kill_after_checkpoint x.checkpoint "${args[@]}")
    files=(x.checkpoint*)
    # (A run that ended before its kill removed its files: its result is compared below all the same.)
    if [ "$state" = killed ]; then
      "$PY" "$HERE/checkpoint_items.py" once "${files[@]}" > once.txt || fail "$dir: $(cat once.txt)"
    fi
  fi
  shopt -u nullglob
  if ! env "$@" "$MPIRUN" -n "$p3" "$BTOB" "${args[@]}" > /dev/null; then
    fail "$dir: the resumed run failed"
  else
    "$PY" "$HERE/h5_same_data.py" ../across_ref/x.h5 x.h5 > cmp.txt || fail "$dir: $(cat cmp.txt)"
    [ -z "$(ls x.checkpoint* 2> /dev/null)" ] || fail "$dir: checkpoint files left: $(ls x.checkpoint*)"
  fi
  [ $failures -eq "$before" ] && echo "ok: $dir: killed at $p1 ranks ($(cat share.txt)), then at $p2 ranks" \
    "${state:+($state)}, resumed at $p3 ranks: the uninterrupted data"
  cd ..
  launch=("$MPIRUN" -n 2 "$BTOB")
}
if [ -n "$MPIRUN" ]; then
  mkdir -p across_ref && (cd across_ref && "$BTOB" bifurcation --r-min 0.08 --r-max 0.4 --r-count 200 \
    --iterations 1000000 --tail 40 --bins 200 --raw --no-plot --threads 1 --quiet --name x --out .) ||
    fail "across: the uninterrupted run failed"
  across 3 2 2                          # the ranks write their rows (parallel HDF5), items no longer cyclic
  across 2 - 3 BTOB_MPI_WRITE=gather    # every part to rank 0 at the end; rank 2 starts with no file
fi

[ $failures -eq 0 ] && echo "resume: all equal to the uninterrupted runs" && exit 0
exit 1
