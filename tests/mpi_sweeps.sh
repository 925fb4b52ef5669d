#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sweeps over MPI ranks (commands::compute, src/commands/execute.hpp): `mpirun -n P btob <command>` for P = 1, 2, 3, 4
# writes the data files of the single-process run bitwise (HDF5 datasets through tests/h5_same_data.py, CSV files and
# standard output byte for byte), whether the ranks write their own rows (parallel HDF5, the sweeps whose parts name
# rows: bifurcation, lyapunov-map, lyapunov-strip, hyperbolicity, hyperbolicity-orbits, leaves) or send them to rank 0
# (BTOB_MPI_WRITE=gather, and every other sweep); no rank holds much more memory than the others; and a rank that
# fails ends the job with one line naming it, a non-zero status and no files.
#
# Usage: mpi_sweeps.sh BTOB [MPIRUN].  CI runs as root: Open MPI then wants --allow-run-as-root, given here
# through its environment variables.  --oversubscribe: three and four ranks on two cores.
set -u
BTOB=$1
MPIRUN=${2:-mpirun}
HERE=$(cd "$(dirname "$0")" && pwd)
PY=/usr/bin/python3
# Whether this btob writes the ranks' rows with parallel HDF5: linked against Open MPI's HDF5 (cmake/ParallelHdf5.cmake).
BTOB_PARALLEL=$(ldd "$BTOB" | grep -q 'libhdf5_openmpi' && echo 1 || echo 0)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# No shared-memory transport warnings from containers without a usable /dev/shm, no help texts.
export OMPI_MCA_btl_base_warn_component_unused=0 OMPI_MCA_orte_base_help_aggregate=1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# same NAME ARGS...: the single process against P = 1, 2, 3, 4 ranks (one OpenMP thread each).
same() {
  local name=$1
  shift
  local ref=$TMP/$name/single
  mkdir -p "$TMP/$name"
  if ! "$BTOB" "$@" --threads 1 --no-plot --quiet --out "$ref" --name x > "$TMP/$name/single.stdout"; then
    fail "$name: the single-process run failed"
    return
  fi
  for P in 1 2 3 4; do
    local out=$TMP/$name/p$P
    if ! "$MPIRUN" -n $P "$BTOB" "$@" --threads 1 --no-plot --quiet --out "$out" --name x > "$out.stdout"; then
      fail "$name: mpirun -n $P failed"
      continue
    fi
    if [ -e "$ref/x.h5" ]; then  # windows verify writes CSV and manifest only (the listing below compares names)
      "$PY" "$HERE/h5_same_data.py" "$ref/x.h5" "$out/x.h5" > "$TMP/cmp.txt" || fail "$name, $P ranks: $(cat "$TMP/cmp.txt")"
    fi
    for f in "$ref"/*.csv; do
      [ -e "$f" ] || continue
      cmp -s "$f" "$out/$(basename "$f")" || fail "$name, $P ranks: $(basename "$f") differs"
    done
    for f in "$ref"/*.tex; do  # --format latex: read back from the CSV the ranks wrote; line 1 is the command line
      [ -e "$f" ] || continue
      cmp -s <(tail -n +2 "$f") <(tail -n +2 "$out/$(basename "$f")") || fail "$name, $P ranks: $(basename "$f") differs"
    done
    [ "$(cd "$ref" && ls)" = "$(cd "$out" && ls)" ] || fail "$name, $P ranks: other files than the single process's"
    # What a summary line may differ in: the output folder and a time in seconds, "(0.2 s)".
    cmp -s <(sed -e "s#$ref#OUT#g" -e 's/([0-9.]* s)//g' "$TMP/$name/single.stdout") \
      <(sed -e "s#$out#OUT#g" -e 's/([0-9.]* s)//g' "$out.stdout") || fail "$name, $P ranks: another standard output"
  done
  echo "ok: $name, P = 1, 2, 3, 4 equal to the single process"
}

# same_columns NAME X_COLUMNS SUMMARY_COLUMNS ARGS...: like same for a command whose CSV files x.csv and
# x_summary.csv hold timings: those columns (cut -d, -f lists) compared, the h5 datasets of none (no x.h5).
same_columns() {
  local name=$1 cols=$2 summary_cols=$3
  shift 3
  local ref=$TMP/$name/single
  mkdir -p "$TMP/$name"
  if ! "$BTOB" "$@" --threads 1 --no-plot --quiet --out "$ref" --name x > /dev/null; then
    fail "$name: the single-process run failed"
    return
  fi
  [ "$(wc -l < "$ref/x.csv")" -gt 1 ] || fail "$name: no rows in x.csv"
  for P in 1 2 3; do
    local out=$TMP/$name/p$P
    if ! "$MPIRUN" -n $P "$BTOB" "$@" --threads 1 --no-plot --quiet --out "$out" --name x > /dev/null; then
      fail "$name: mpirun -n $P failed"
      continue
    fi
    cmp -s <(cut -d, -f"$cols" "$ref/x.csv") <(cut -d, -f"$cols" "$out/x.csv") || fail "$name, $P ranks: x.csv differs"
    cmp -s <(cut -d, -f"$summary_cols" "$ref/x_summary.csv") <(cut -d, -f"$summary_cols" "$out/x_summary.csv") ||
      fail "$name, $P ranks: x_summary.csv differs"
    [ "$(cd "$ref" && ls)" = "$(cd "$out" && ls)" ] || fail "$name, $P ranks: other files than the single process's"
  done
  echo "ok: $name, P = 1, 2, 3 equal to the single process (timings aside)"
}

# same_stdout NAME ARGS...: a command that prints its result (no files), P = 1, 2, 3 against the single process.
same_stdout() {
  local name=$1
  shift
  mkdir -p "$TMP/$name"
  if ! "$BTOB" "$@" --threads 1 --quiet > "$TMP/$name/single.stdout"; then
    fail "$name: the single-process run failed"
    return
  fi
  [ -s "$TMP/$name/single.stdout" ] || fail "$name: the single process printed nothing"
  for P in 1 2 3; do
    if ! "$MPIRUN" -n $P "$BTOB" "$@" --threads 1 --quiet > "$TMP/$name/p$P.stdout"; then
      fail "$name: mpirun -n $P failed"
      continue
    fi
    cmp -s "$TMP/$name/single.stdout" "$TMP/$name/p$P.stdout" || fail "$name, $P ranks: another standard output"
  done
  echo "ok: $name, P = 1, 2, 3 print what the single process prints"
}

# The ranks' own rows against rows gathered to rank 0 (the way of a build without parallel HDF5).
gathered() {
  local name=$1
  shift
  local out=$TMP/$name/gathered
  BTOB_MPI_WRITE=gather "$MPIRUN" -n 3 "$BTOB" "$@" --threads 1 --no-plot --quiet --out "$out" --name x ||
    fail "$name: mpirun -n 3 with BTOB_MPI_WRITE=gather failed"
  "$PY" "$HERE/h5_same_data.py" "$TMP/$name/single/x.h5" "$out/x.h5" > "$TMP/cmp.txt" ||
    fail "$name, rows gathered: $(cat "$TMP/cmp.txt")"
  echo "ok: $name, rows gathered to rank 0 equal to the single process"
}

# rank_written NAME: with parallel HDF5, the runs of `same NAME` on 2, 3 and 4 ranks wrote their rows themselves
# (the manifest records the bytes they wrote), so the comparisons above were of rank-written datasets.
rank_written() {
  [ "$BTOB_PARALLEL" = 1 ] || return 0
  for P in 2 3 4; do
    grep -q '"mpi_rows_bytes": [1-9]' "$TMP/$1/p$P/x.json" || fail "$1, $P ranks: the ranks did not write their rows"
  done
}

# rows_sweep NAME ARGS...: a sweep whose ranks write their rows: `same`, checked to be rank-written, and `gathered`.
rows_sweep() {
  same "$@"
  rank_written "$1"
  gathered "$@"
}

# Sizes: each item costs about the same, a few items per rank, r ranges with chaos, windows and invariant curves.
rows_sweep bifurcation bifurcation --r-min 0.08 --r-max 0.4 --r-count 41 --iterations 3000 --tail 40 --bins 200 --raw
# Its summary table's lines are written by the ranks too (after rank 0's header); --format latex reads them back.
# r-min 0.0717: the windows overlay's bounds of n = 1..400, computed in shares by the ranks (extras::share_overlays).
same lyapunov-map lyapunov-map --r-min 0.0717 --r-max 0.3 --r-count 23 --iterations 1000 --transient 200 --blocks 5 \
  --format latex
rank_written lyapunov-map
# Float: the check of every k-th r value in double is computed in the parts (per r value) since they keep their rows.
same lyapunov-map-float lyapunov-map --r-min 0.17 --r-max 0.172 --r-count 70 --grid random:4 --iterations 3000 \
  --transient 200 --blocks 5 --precision float
rows_sweep lyapunov-strip lyapunov-strip --r 0.11 --grid strip:30x20 --iterations 500 --transient 100
same basins basins --r 0.2 --grid strip:24x17 --replicates 1 --transient 500 --iterations 300 --max-period 200 \
  --lyap-iterations 400 --refine-factor 2
same basins-r basins-r --r-values 0.11 0.15 0.2 0.25 --grid random:60 --boundary-grid sphere:40x40 --transient 500 \
  --iterations 300 --max-period 200 --lyap-iterations 400 --refine-factor 2
# The label map is the ranks' rows; the landing law and mass are computed per r in the parts.
rows_sweep leaves leaves --r-min 0.18 --r-max 0.9 --r-count 6 --grid sphere:30x30 --leaf-iterations 500 \
  --transient 500 --iterations 300 --max-period 200
# The cells are the ranks' rows; the printed expanding fraction and s1's extremes are counted in the parts.
same hyperbolicity hyperbolicity --r 0.11 --grid strip:60x30
rank_written hyperbolicity
# r up to 0.31: degenerate orbits (NaN angles) beside pooled quantiles and histograms per r.  The per-orbit arrays
# (uint8 and double) and the histograms are the ranks' rows; lambda1's summary per r is computed in the parts.
rows_sweep hyperbolicity-orbits hyperbolicity-orbits --r-min 0.09 --r-max 0.31 --r-count 7 --grid random:6 \
  --iterations 1000 --transient 500 --backward 500 --bins 30
# r = 0.3: four groups of measures (invariant curves) whose heads lie on different ranks.
same measure measure --r 0.3 --grid random:12 --iterations 20000 --transient 1000 --bins 50

# Sweeps over n (the cost of an n grows with it) and over the words of the atlas; small n and word lengths.
same_stdout windows-poly windows poly --n 1..7
same_stdout windows-bounds windows bounds --n 1..20 --certify --digits 15
same windows-verify windows verify --n 2..7 --iterations 2000 --per-n 10 --tail 1000
# The precision study's seconds columns time each bound: compared without them (x.csv's last column, the summary's).
same_columns windows-precision 1-6 1-4 windows precision --n 1..8 --mpfr-digits 20
# Length 7: 5 words of length <= 7 stable; the check's 33 r values are items too (their patterns and counts).
same pattern-atlas pattern atlas --max-length 7 --ics 40 --iterations 2000 --tail 500 --max-period 200
same pattern-atlas-feasible pattern atlas --feasible --max-length 5

# The comparison can fail: another request (one more r value) differs from the reference.
"$BTOB" lyapunov-map --r-min 0.0717 --r-max 0.3 --r-count 24 --iterations 1000 --transient 200 --blocks 5 --threads 1 \
  --no-plot --quiet --out "$TMP/other" --name x
"$PY" "$HERE/h5_same_data.py" "$TMP/lyapunov-map/single/x.h5" "$TMP/other/x.h5" > /dev/null &&
  fail "h5_same_data.py found two different requests equal"

# A bad input on every rank: the single process's one line, said once, exit 2, nothing written.
"$MPIRUN" -n 2 "$BTOB" bifurcation --r-min 2 --out "$TMP/bad" > "$TMP/out.txt" 2> "$TMP/err.txt"
code=$?
[ $code -eq 2 ] || fail "bad input on every rank: exit $code, expected 2"
grep -c '^btob: error: r-min: got 2' "$TMP/err.txt" | grep -qx 1 || fail "bad input: not one line: $(cat "$TMP/err.txt")"
[ ! -e "$TMP/bad" ] || fail "bad input: $TMP/bad was created"
# The same for an input that only the pair of fields makes bad (r-min > r-max): btob's one line, said once, and no
# MPI_ABORT banner (mpirun's own notice of a non-zero exit status remains: it is mpirun's, not btob's).
for cmd in lyapunov-map bifurcation; do
  "$MPIRUN" -n 2 "$BTOB" $cmd --r-min 0.3 --r-max 0.1 --out "$TMP/bad" > "$TMP/out.txt" 2> "$TMP/err.txt"
  code=$?
  [ $code -eq 2 ] || fail "$cmd r-min > r-max: exit $code, expected 2"
  [ "$(grep '^btob' "$TMP/err.txt")" = "btob: error: r-max: got 0.1, expected a value in (r-min = 0.3, 1)" ] ||
    fail "$cmd r-min > r-max: not one line: $(cat "$TMP/err.txt")"
  ! grep -q MPI_ABORT "$TMP/err.txt" || fail "$cmd r-min > r-max: an MPI_ABORT banner"
done

# One rank fails before the work (its request is not the others'): one line naming rank 1, non-zero, no files.
"$MPIRUN" -n 1 "$BTOB" bifurcation --r-count 50 --iterations 200 --tail 10 --out "$TMP/split" --quiet --no-plot : \
  -n 1 "$BTOB" bifurcation --r-count 0 --iterations 200 --tail 10 --out "$TMP/split" --quiet --no-plot \
  > "$TMP/out.txt" 2> "$TMP/err.txt"
code=$?
[ $code -ne 0 ] || fail "a failing rank 1: exit 0"
grep -q '^btob: rank 1: r-count: got 0' "$TMP/err.txt" || fail "a failing rank 1: no line naming it: $(cat "$TMP/err.txt")"
[ ! -e "$TMP/split" ] || fail "a failing rank 1: $TMP/split was created"

# A rank fails during the work (out of memory: 1 GB of raw tails under a 700 MB address-space limit), after the
# others started; an existing result in the output folder stays as it was.
mkdir -p "$TMP/kept" && echo old > "$TMP/kept/x.h5"
args=(bifurcation --r-count 2000 --iterations 4000 --tail 4000 --raw --out "$TMP/kept" --name x --quiet --no-plot --threads 1)
"$MPIRUN" -n 1 "$BTOB" "${args[@]}" : -n 1 bash -c 'ulimit -v 700000; exec "$0" "$@"' "$BTOB" "${args[@]}" \
  > "$TMP/out.txt" 2> "$TMP/err.txt"
code=$?
[ $code -ne 0 ] || fail "out of memory on rank 1: exit 0"
# The line names the rank and its items (cyclic: 1, 3, 5, ... of 2000 r values).
grep -q '^btob: rank 1: items 1, 3, 5, \.\.\. of 2000: out of memory' "$TMP/err.txt" || fail "out of memory on rank 1: $(cat "$TMP/err.txt")"
[ "$(ls "$TMP/kept")" = "x.h5" ] && [ "$(cat "$TMP/kept/x.h5")" = old ] || fail "out of memory: the old result changed"

# A rank fails inside the ranks' collective write of NAME.h5 (BTOB_MPI_ROWS_FAIL=K, the write's fault injection), with
# the file open on every rank: one line naming the rank and the file, a non-zero status, within the timeout (a rank
# that threw there unwound through a collective close the others never matched, and the job hung), and neither the
# result nor rank 0's hidden staging folder left in the output folder.  Rank 1: another rank fails under rank 0;
# rank 0: the writer itself.
if [ "$BTOB_PARALLEL" = 1 ]; then
  for k in 1 0; do
    rm -rf "$TMP/abort" && mkdir -p "$TMP/abort"
    BTOB_MPI_ROWS_FAIL=$k timeout 60 "$MPIRUN" -n 3 "$BTOB" lyapunov-map --r-min 0.1 --r-max 0.3 --r-count 30 \
      --grid random:4 --iterations 50 --transient 1 --threads 1 --out "$TMP/abort" --quiet --no-plot \
      > "$TMP/out.txt" 2> "$TMP/err.txt"
    code=$?
    [ $code -ne 0 ] && [ $code -ne 124 ] || fail "rank $k failing in the write: exit $code (124: hung)"
    grep -q "^btob: rank $k: cannot write the ranks' rows into .*failed on purpose" "$TMP/err.txt" ||
      fail "rank $k failing in the write: no line naming it: $(cat "$TMP/err.txt")"
    [ -z "$(ls -A "$TMP/abort")" ] || fail "rank $k failing in the write left: $(ls -A "$TMP/abort")"
  done
fi

# `btob run SCENE.toml` splits the same way.
cat > "$TMP/scene.toml" << 'EOF'
command = "bifurcation"
[args]
r-min = 0.1
r-max = 0.2
r-count = 13
iterations = 500
tail = 20
bins = 100
EOF
"$BTOB" run "$TMP/scene.toml" --out "$TMP/scene1" --quiet --no-plot --threads 1 &&
  "$MPIRUN" -n 3 "$BTOB" run "$TMP/scene.toml" --out "$TMP/scene3" --quiet --no-plot --threads 1 &&
  "$PY" "$HERE/h5_same_data.py" "$TMP/scene1/scene.h5" "$TMP/scene3/scene.h5" > /dev/null ||
  fail "btob run SCENE.toml under mpirun -n 3"

# Memory: each rank's peak resident set (tests/peak_rss.py) for a 86 MB result of per-orbit exponents (1200 r values
# x 1000 orbits x 9 doubles): every rank holds its share of it, so the largest peak is within 15% of the median.
# With the rows gathered to rank 0, rank 0 holds the whole result and the same check fails (the check can fail).
big=(lyapunov-map --r-min 0.08 --r-max 0.3 --r-count 1200 --grid random:1000 --iterations 60 --transient 6 --blocks 5
     --threads 1 --no-plot --quiet --name x)
for mode in rows gather; do
  rm -f "$TMP/rss_$mode"
  BTOB_MPI_WRITE=$mode "$MPIRUN" -n 3 "$PY" "$HERE/peak_rss.py" "$TMP/rss_$mode" "$BTOB" "${big[@]}" \
    --out "$TMP/big_$mode" || fail "memory ($mode): the run failed"
  read -r top median <<< "$("$PY" "$HERE/peak_rss.py" --peaks "$TMP/rss_$mode")"
  echo "peak resident set per rank ($mode; largest $top KB, median $median KB): $(sort -n "$TMP/rss_$mode" | awk '{printf "%s%d MB", (NR > 1 ? ", " : ""), $2 / 1024}')"
  within=$(awk -v t="$top" -v m="$median" 'BEGIN {print (t <= 1.15 * m) ? 1 : 0}')
  if [ "$mode" = rows ] && [ "$BTOB_PARALLEL" = 1 ] && [ "$within" != 1 ]; then
    fail "memory: the largest peak $top KB is over 1.15 x the median $median KB"
  fi
  if [ "$mode" = gather ] && [ "$within" = 1 ]; then
    fail "memory: rows gathered to rank 0 but its peak $top KB is within 1.15 x the median $median KB (no power)"
  fi
done
"$PY" "$HERE/h5_same_data.py" "$TMP/big_rows/x.h5" "$TMP/big_gather/x.h5" > "$TMP/cmp.txt" ||
  fail "memory runs: $(cat "$TMP/cmp.txt")"

[ $failures -eq 0 ] && echo "mpi sweeps: all equal, failures reported" && exit 0
exit 1
