#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Scaling model of `mpirun -n P btob lyapunov-map` (README, "Sweeps over MPI"), from the measurements of
analyses/mpi_scaling.sh.

Usage: mpi_model.py RESULTS_DIR   (reads benchmark.csv and gather.csv, writes projection.csv, prints markdown)

Measured here (one run on this shared 2-core machine):
  s        tangent-cocycle steps per second per core: the P = 1 run (one thread) of gather.csv
  b        bytes gathered per orbit: bytes_gathered / orbits not on rank 0 (P = 2, 3)
  g        gather rate on this machine (shared memory): bytes_gathered / gather_seconds of the large result
  merge    rank 0 unpacking and merging (summary per r included): result bytes / merge_seconds, large result,
           the slower of P = 2, 3
Assumed for a commodity InfiniBand cluster (stated, not measured):
  BETA     12.5e9 B/s   node link (EDR, 100 Gb/s); rank 0 receives everything through its one link
  ALPHA    2e-6 s       latency per message (three messages per rank)
  WRITE    1e9 B/s      one HDF5 writer on a parallel file system
  LAUNCH   0.5 s + 0.01 s per node: mpirun/srun start-up
  One rank per node with one OpenMP thread per core; per-core speed as here (the kernel is compute bound: an
  orbit's state stays in registers and cache, the recorder writes once per block); the items (r values) cost the
  same, so the cyclic split leaves no imbalance beyond one item.
"""
import csv
import math
import sys

BETA, ALPHA, WRITE = 12.5e9, 2e-6, 1e9
TARGET = dict(r=1_000_000, ic=1024, iterations=100_000, transient=1000)  # 1e14 steps of the tangent cocycle
RECORDER_BYTES = 8 * (13 + 3 * (10 + 1))  # TangentRecorder per orbit, 10 blocks (lyapunov/tangent.hpp)


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main(d):
    bench = read(f"{d}/benchmark.csv")
    gather = read(f"{d}/gather.csv")
    one = next(g for g in gather if g["ranks"] == "1")
    s = int(one["r_count"]) * 32 * 1.1 * int(one["iterations"]) / float(one["compute_max_seconds"])
    per_orbit, rates, merges = [], [], []
    for g in gather:
        P, r_count = int(g["ranks"]), int(g["r_count"])
        if P == 1:
            continue
        # rank 0 keeps items i = 0 mod P: ceil(r_count / P) of them
        away = (r_count - math.ceil(r_count / P)) * 32
        per_orbit.append(float(g["bytes_gathered"]) / away)
        if int(g["r_count"]) == max(int(x["r_count"]) for x in gather):  # the large result: rates
            rates.append(float(g["bytes_gathered"]) / float(g["gather_seconds"]))
            merges.append(r_count * 32 * per_orbit[-1] / float(g["merge_seconds"]))
    b = max(per_orbit)
    merge_rate = min(merges)

    def median(v):
        return sorted(v)[len(v) // 2]

    def col(name):
        return {c: [float(x[name]) for x in bench if x["config"] == c] for c in ("openmp", "mpi")}


    print("Measured (analyses/mpi_scaling.sh, one run, 2 shared cores):\n")
    print("| run | wall (s) | CPU (s) | work (s) |")
    print("|---|---|---|---|")
    for x in bench:
        print(f"| {x['config']} {x['ranks']} rank(s) x {x['threads']} thread(s), rep {x['rep']} | "
              f"{float(x['wall_seconds']):.2f} | {float(x['cpu_seconds']):.2f} | {float(x['work_seconds']):.2f} |")
    print("\nEfficiency of 2 ranks x 1 thread against 1 rank x 2 threads (OpenMP time / MPI time, same repetition):")
    for name in ("wall_seconds", "cpu_seconds", "work_seconds"):
        t = col(name)
        e = [o / m for o, m in zip(t["openmp"], t["mpi"])]
        print(f"- {name.split('_')[0]}: {', '.join(f'{x:.3f}' for x in e)} (median {median(e):.3f})")
    print()
    print("| ranks | r values x steps | work per rank (s, min..max) | wait at barrier (s) | bytes gathered | gather (s) | "
          "merge (s) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|")
    for g in gather:
        print(f"| {g['ranks']} | {g['r_count']} x {int(g['iterations']) * 11 // 10} | {float(g['compute_min_seconds']):.2f}..{float(g['compute_max_seconds']):.2f} | "
              f"{float(g['wait_seconds']):.3f} | {int(g['bytes_gathered'])} | {float(g['gather_seconds']):.4f} | "
              f"{float(g['merge_seconds']):.4f} | {float(g['wall_seconds']):.2f} |")
    print(f"\nDerived: s = {s:.3g} steps/s per core; {b:.1f} bytes gathered per orbit (5 doubles + item indices); "
          f"gather rate here {min(rates) / 1e9:.2f} GB/s (shared memory, oversubscribed); merge {merge_rate / 1e9:.2f} GB/s "
          f"of result\n")

    n_orbits = TARGET["r"] * TARGET["ic"]
    total_steps = n_orbits * (TARGET["iterations"] + TARGET["transient"])
    result_bytes = n_orbits * b
    rows = []
    for cores in (2, 64):
        for nodes in (16, 64, 256):
            compute = total_steps / (nodes * cores * s)
            gather_t = result_bytes * (nodes - 1) / nodes / BETA + 3 * (nodes - 1) * ALPHA
            merge_t = result_bytes / merge_rate
            write_t = result_bytes / WRITE
            launch = 0.5 + 0.01 * nodes
            wall = compute + gather_t + merge_t + write_t + launch
            mem_rank = n_orbits / nodes * (RECORDER_BYTES + b)
            mem_root = mem_rank + 2 * result_bytes
            rows.append(dict(nodes=nodes, cores_per_node=cores, compute_s=compute, gather_s=gather_t, merge_s=merge_t,
                             write_s=write_t, launch_s=launch, wall_s=wall, efficiency=compute / wall,
                             memory_per_rank_gb=mem_rank / 1e9, memory_rank0_gb=mem_root / 1e9))
    with open(f"{d}/projection.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    print(f"Projection: {TARGET['r']:.0e} r x {TARGET['ic']} orbits x ({TARGET['iterations']:.0e} + "
          f"{TARGET['transient']}) steps = {total_steps:.3g} steps; result {result_bytes / 1e9:.1f} GB gathered to rank 0\n")
    print("| nodes x cores | compute | gather | merge | write | wall | efficiency | memory per rank | rank 0 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['nodes']} x {r['cores_per_node']} | {r['compute_s']:.3g} s | {r['gather_s']:.2g} s | "
              f"{r['merge_s']:.2g} s | {r['write_s']:.2g} s | {r['wall_s'] / 3600:.3g} h | {r['efficiency']:.3f} | "
              f"{r['memory_per_rank_gb']:.3g} GB | {r['memory_rank0_gb']:.3g} GB |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
