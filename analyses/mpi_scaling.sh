#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# MPI against OpenMP on the Lyapunov-map workload, and what the gather to rank 0 costs: writes results/mpi/.
# Usage: analyses/mpi_scaling.sh [BTOB_BINARY] [R_COUNT]   (default build/release/btob, 5000 r values)
#   benchmark.csv  1 rank x 2 threads against 2 ranks x 1 thread, alternated (A B A B A B): wall and CPU time of the
#                  whole command (mpirun and its ranks), and the work's time (the kernel's; for MPI the slowest
#                  rank's run_part).  CPU time is the steadier measure on a shared machine: wall time depends on
#                  how many cores the other users leave.
#   gather.csv     P = 1, 2, 3 ranks of 1 thread (3 oversubscribed on 2 cores), every row gathered to rank 0 (the
#                  design before the ranks wrote their own rows: BTOB_MPI_WRITE=gather): work per rank, wait at the
#                  barrier, bytes gathered to rank 0 and the gather's time
#   rows.csv       P = 2, 3, 4 ranks of 1 thread on a large result (10 x R_COUNT r values x 32 orbits, 110 steps:
#                  ~115 MB of per-orbit exponents) and on a tiny one (the write's fixed cost), each twice: the ranks
#                  writing their own rows (parallel HDF5) and the rows gathered to rank 0 (BTOB_MPI_WRITE=gather):
#                  bytes and seconds of the ranks' write, bytes gathered, gather and merge, rank 0's time alone after
#                  the gather (its manifest's mpi_root_seconds), the slowest rank's work, wall time, and the peak
#                  resident set of every rank (tests/peak_rss.py); then 1e6 r values of one orbit on 2 ranks: what
#                  rank 0 still does per r value at scale (merge, its own datasets, the per-r table)
#   collectives.csv P = 2, 3, 4 ranks on the tiny result (ranks writing their rows), one more run each with the
#                  collectives counted (analyses/mpi_count.c, preloaded; apart from the timed runs, since counting adds
#                  its own time): per MPI collective, its class (tree: log2 P rounds; pair: P - 1 messages, the
#                  all-to-all exchanges and the MPI-IO collectives), the calls per rank (largest and median over the
#                  ranks) and the largest time in it over the ranks
#   launch.csv     mpirun -n P btob --version, P = 1..4: the launch's cost here
#   projection.csv the scaling model (analyses/mpi_model.py), from gather.csv, rows.csv, collectives.csv and launch.csv
# The machine is shared: quote the ratios of one run, not absolute times.
set -euo pipefail
cd "$(dirname "$0")/.."
btob="${1:-build/release/btob}"
r_count="${2:-5000}"
out=results/mpi
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The collectives' counter, preloaded into the counted runs below.
if ! command -v mpicc > /dev/null; then
  echo "mpi_scaling.sh: mpicc not found: it builds analyses/mpi_count.c, the counter of the MPI collectives" >&2
  exit 1
fi
mpicc -shared -fPIC -O2 -o "$tmp/mpi_count.so" analyses/mpi_count.c
# The workload: r in [0.0717, 0.6] x the 32-point grid of Section 4 x 1e4 averaged steps (+1e3 transient).
work=(lyapunov-map --r-min 0.0717 --r-max 0.6 --r-count "$r_count" --grid paper --iterations 10000 --transient 1000
      --no-plot --quiet --name x)
attr() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(j.get(sys.argv[2], ''))" "$@"; }
wall() { local t0 t1; t0=$(date +%s.%N); "$@"; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
# "wall,cpu": elapsed and CPU seconds (user + system) of a command and its children (mpirun's ranks included).
timed() { /usr/bin/time -f "%e,%U,%S" -o "$tmp/time" "$@" && awk -F, '{printf "%s,%.2f", $1, $2 + $3}' "$tmp/time"; }

echo "config,ranks,threads,rep,wall_seconds,cpu_seconds,work_seconds,steps" > "$out/benchmark.csv.tmp"
steps=$((r_count * 32 * 11000))
for rep in 1 2 3; do
  t=$(timed "$btob" "${work[@]}" --threads 2 --out "$tmp/a")
  echo "openmp,1,2,$rep,$t,$(attr "$tmp/a/x.json" iteration_seconds),$steps" >> "$out/benchmark.csv.tmp"
  t=$(timed mpirun -n 2 "$btob" "${work[@]}" --threads 1 --out "$tmp/b")
  echo "mpi,2,1,$rep,$t,$(attr "$tmp/b/x.json" mpi_compute_seconds_max),$steps" >> "$out/benchmark.csv.tmp"
  /usr/bin/python3 tests/h5_same_data.py "$tmp/a/x.h5" "$tmp/b/x.h5" > /dev/null  # same numbers, or stop here
done
mv "$out/benchmark.csv.tmp" "$out/benchmark.csv"

echo "ranks,r_count,iterations,compute_min_seconds,compute_max_seconds,wait_seconds,gather_seconds,bytes_gathered,merge_seconds,wall_seconds" \
  > "$out/gather.csv.tmp"
# The workload at P = 1, 2, 3, then a 10x larger result with 100x fewer steps (P = 2, 3): the gather's and the
# merge's rates on 64 MB rather than 6 MB, where fixed costs no longer dominate.
for run in "1 $r_count 10000" "2 $r_count 10000" "3 $r_count 10000" "2 $((10 * r_count)) 100" "3 $((10 * r_count)) 100"; do
  read -r P R N <<< "$run"
  w=$(wall env BTOB_MPI_WRITE=gather mpirun -n "$P" "$btob" "${work[@]}" --r-count "$R" --iterations "$N" \
      --transient $((N / 10)) --threads 1 --out "$tmp/g$P")
  j="$tmp/g$P/x.json"
  if [ "$P" -eq 1 ]; then  # one rank runs run() itself: its work is the kernel's time, nothing is gathered
    echo "1,$R,$N,$(attr "$j" iteration_seconds),$(attr "$j" iteration_seconds),0,0,0,0,$w" >> "$out/gather.csv.tmp"
  else
    echo "$P,$R,$N,$(attr "$j" mpi_compute_seconds_min),$(attr "$j" mpi_compute_seconds_max),$(attr "$j" mpi_wait_seconds),$(attr "$j" mpi_gather_seconds),$(attr "$j" mpi_gathered_bytes),$(attr "$j" mpi_merge_seconds),$w" \
      >> "$out/gather.csv.tmp"
  fi
done
mv "$out/gather.csv.tmp" "$out/gather.csv"

echo "mode,ranks,r_count,orbits,rows_bytes,rows_seconds,rows_seconds_min,bytes_gathered,gather_seconds,merge_seconds,root_seconds,compute_max_seconds,share_seconds,wall_seconds,peak_kb_max,peak_kb_median" \
  > "$out/rows.csv.tmp"
# rows_run MODE P R ORBITS ARGS...: one run of the workload with ARGS, its manifest's MPI statistics and the ranks' peaks
# as a line of rows.csv (root_seconds: rank 0 alone after the gather, the ranks' write included; rows mode only;
# share_seconds: rank 0 in the overlays' shares before the run).
rows_run() {
  local mode=$1 P=$2 R=$3 orbits=$4
  shift 4
  rm -f "$tmp/rss"
  w=$(wall env BTOB_MPI_WRITE=$mode mpirun -n "$P" /usr/bin/python3 tests/peak_rss.py "$tmp/rss" "$btob" "${work[@]}" \
      --r-count "$R" "$@" --threads 1 --out "$tmp/w")
  j="$tmp/w/x.json"
  local peaks
  peaks=$(/usr/bin/python3 tests/peak_rss.py --peaks "$tmp/rss" | tr ' ' ,)
  local a=""
  for k in mpi_rows_bytes mpi_rows_seconds mpi_rows_seconds_min mpi_gathered_bytes mpi_gather_seconds \
           mpi_merge_seconds mpi_root_seconds mpi_compute_seconds_max mpi_share_seconds; do a="$a$(attr "$j" $k),"; done
  echo "$mode,$P,$R,$orbits,$a$w,$peaks" >> "$out/rows.csv.tmp"
}
for R in $((10 * r_count)) 64; do
  for P in 2 3 4; do
    for mode in rows gather; do rows_run "$mode" "$P" "$R" $((R * 32)) --iterations 100 --transient 10; done
  done
done
# Rank 0's share at scale: 1e6 r values of one orbit each (what rank 0 still receives, merges and writes alone).
rows_run rows 2 1000000 1000000 --grid random:1 --iterations 10 --transient 1
mv "$out/rows.csv.tmp" "$out/rows.csv"

echo "ranks,function,class,calls_max,calls_median,seconds_max" > "$out/collectives.csv.tmp"
# The tiny result again, the ranks writing their rows, with every rank's collectives counted (rank<R>.csv at
# MPI_Finalize), then taken over the ranks (largest and median calls, largest time; a rank that did not call a
# function counts 0 calls of it).
for P in 2 3 4; do
  mkdir -p "$tmp/count$P"
  BTOB_MPI_WRITE=rows BTOB_MPI_COUNT_DIR="$tmp/count$P" mpirun -n "$P" -x LD_PRELOAD="$tmp/mpi_count.so" \
    -x BTOB_MPI_COUNT_DIR "$btob" "${work[@]}" --r-count 64 --iterations 100 --transient 10 --threads 1 \
    --out "$tmp/c" > /dev/null
  /usr/bin/python3 - "$tmp/count$P" "$P" >> "$out/collectives.csv.tmp" <<'EOF'
import csv, sys
d, P = sys.argv[1], int(sys.argv[2])
by = {}
for rank in range(P):
    with open(f"{d}/rank{rank}.csv") as f:
        for x in csv.DictReader(f):
            by.setdefault((x["function"], x["class"]), []).append((int(x["calls"]), float(x["seconds"])))
for (function, kind), v in by.items():
    calls = sorted([c for c, _ in v] + [0] * (P - len(v)))
    print(f"{P},{function},{kind},{calls[-1]},{calls[P // 2]},{max(t for _, t in v):.6f}")
EOF
done
mv "$out/collectives.csv.tmp" "$out/collectives.csv"

echo "ranks,wall_seconds" > "$out/launch.csv.tmp"
for P in 1 2 3 4; do
  for rep in 1 2 3; do echo "$P,$(wall sh -c "mpirun -n $P '$btob' --version > /dev/null")" >> "$out/launch.csv.tmp"; done
done
mv "$out/launch.csv.tmp" "$out/launch.csv"
/usr/bin/python3 analyses/mpi_model.py "$out" | tee "$out/model.md"
"$(dirname "$btob")/btob_manifest" "$out/manifest.json" "analyses/mpi_scaling.sh $btob $r_count" \
  benchmark.csv gather.csv rows.csv collectives.csv launch.csv projection.csv model.md
