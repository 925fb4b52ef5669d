#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Scaling model of `mpirun -n P btob lyapunov-map` (docs/guides/mpi.md), from the measurements of
analyses/mpi_scaling.sh.

Usage: mpi_model.py RESULTS_DIR   (reads benchmark.csv, gather.csv, rows.csv, collectives.csv, launch.csv; writes
projection.csv, prints markdown)

Measured here (one run on this shared 2-core machine):
  s        tangent-cocycle steps per second per core: the P = 1 run (one thread) of gather.csv
  b, p     bytes of result per orbit (5 doubles gathered before; 9 doubles written now) and per r value (the per-r
           summary's 9 doubles and its table line, written by the ranks too): rows.csv's rows_bytes = orbits b + R p,
           from the 32-orbit runs and the 1-orbit run
  t        bytes each rank still sends rank 0 per r value when it keeps its rows (summary per r, item indices):
           rows.csv's bytes_gathered / r values not on rank 0
  c(P)     the ranks' write's fixed cost (collective open, exchange plan, close) on P ranks:
             c(P) = c_2 + ALPHA [n_tree (log2 P - 1) + n_pair (P - 2)]
           c_2: the write's time on the tiny result at P = 2 (rows.csv's rows_seconds, median), everything that does
           not grow with P (creating, opening and closing the file, HDF5's own work, the collectives on 2 ranks);
           n_tree, n_pair: the collective calls per rank, counted (collectives.csv, analyses/mpi_count.c) at the
           largest P measured, by how their latency grows: n_tree calls of log2 P rounds (barrier, broadcast,
           reductions, scans, gathers), n_pair calls of P - 1 messages (the all-to-all exchanges, and the MPI-IO
           collectives, btob's and HDF5's, whose exchange between aggregators is pairwise: P - 1 messages each is an
           upper bound).  All of the run's collectives are counted, not only the write's: an upper bound too.  The tiny
           result's write at P = 3 and 4 is not used: this machine has 2 cores, and the longer write there is the
           ranks waiting for a core, not the collectives' growth with P
  m        rank 0's merge per r value (unpacking and placing the per-r summaries): merge_seconds / r values of the
           1e6-r run
  w        the windows overlay's bounds, computed in shares by the ranks before the run (extras::share_overlays):
           w / P, w = rank 0's mpi_share_seconds x min(P, cores here) of the tiny runs (median: P ranks on this
           machine's cores run their shares side by side only up to its cores); counted with rank 0's time below
  a, tau   what rank 0 does alone after the gather besides the ranks' write (the merge, the result's overlays, its
           own datasets (r), deflated, the table's header, the manifest), a + tau R: its manifest's mpi_root_seconds minus
           the ranks' write; a from the tiny runs (median), tau from the 1e6-r run.  Measured with one thread per
           rank and not scaled down for more threads: the table and the deflate run on one thread
  (the ranks' write rate here, rows_bytes / rows_seconds, is one shared disk's and is shown, not projected)
Assumed for a commodity InfiniBand cluster (stated, not measured):
  BETA     12.5e9 B/s   node link (EDR, 100 Gb/s)
  ALPHA    2e-6 s       latency per message (three messages per rank to rank 0; per round or message of the write's
                        collectives in c(P))
  FS       1, 10, 100, 1000 GB/s: the parallel file system's aggregate bandwidth, a parameter; the ranks' write runs at
           min(FS, nodes x BETA), after the exchange that gives each rank one block of rows (its share over its link)
  LAUNCH   0.5 s + 0.01 s per node: mpirun/srun start-up (shown apart: it is the launcher's, the same for any job)
  One rank per node with one OpenMP thread per core (the ranks are the file's writers); per-core speed as here;
  the r values cost the same, so the cyclic split leaves no imbalance beyond one item.
"""
import csv
import math
import os
import sys

BETA, ALPHA, WRITE = 12.5e9, 2e-6, 1e9
FS = (1e9, 10e9, 100e9, 1000e9)
TARGET = dict(r=1_000_000, ic=1024, iterations=100_000, transient=1000)  # 1e14 steps of the tangent cocycle
RECORDER_BYTES = 8 * (13 + 3 * (10 + 1))  # TangentRecorder per orbit, 10 blocks (lyapunov/tangent.hpp)


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def gathered_projection(s, b, merge_rate, n_orbits, total_steps, m):
    """The design before: every rank's rows to rank 0, merged and written there by one HDF5 writer, and rank 0's
    share per r value as now (root_alone: the overlays, the per-r table)."""
    rows = []
    result_bytes = n_orbits * b
    for cores in (2, 64):
        for nodes in (16, 64, 256):
            compute = total_steps / (nodes * cores * s)
            gather_t = result_bytes * (nodes - 1) / nodes / BETA + 3 * (nodes - 1) * ALPHA
            merge_t = result_bytes / merge_rate + root_alone(m)
            write_t = result_bytes / WRITE
            launch = 0.5 + 0.01 * nodes
            io = gather_t + merge_t + write_t
            rows.append(dict(design="gathered", fs_gbs=WRITE / 1e9, nodes=nodes, cores_per_node=cores,
                             compute_s=compute, gather_s=gather_t, merge_s=merge_t, write_s=write_t, launch_s=launch,
                             wall_s=compute + io + launch, efficiency=compute / (compute + io),
                             efficiency_launch=compute / (compute + io + launch),
                             memory_per_rank_gb=n_orbits / nodes * (RECORDER_BYTES + b) / 1e9,
                             memory_rank0_gb=(n_orbits / nodes * (RECORDER_BYTES + b) + 2 * result_bytes) / 1e9))
    return rows


def rows_measured(d):
    print("| rows | ranks | r values | bytes written by the ranks | their write (s, slowest) | bytes gathered | "
          "gather (s) | merge (s) | rank 0 alone (s) | wall (s) | peak per rank, largest / median (MB) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for x in read(f"{d}/rows.csv"):
        def num(k, f="{:.4f}"):
            return f.format(float(x[k])) if x[k] else "-"
        print(f"| {x['mode']} | {x['ranks']} | {x['r_count']} | {x['rows_bytes'] or 0} | {num('rows_seconds')} | "
              f"{x['bytes_gathered']} | {num('gather_seconds')} | {num('merge_seconds')} | {num('root_seconds')} | {num('wall_seconds', '{:.2f}')} | "
              f"{int(x['peak_kb_max']) / 1024:.0f} / {int(x['peak_kb_median']) / 1024:.0f} |")


def rows_parameters(d):
    rows = [x for x in read(f"{d}/rows.csv") if x["mode"] == "rows"]
    big = [x for x in rows if int(x["r_count"]) >= 1000]
    big = [x for x in big if int(x["orbits"]) > int(x["r_count"])]  # 32 orbits per r
    at_scale = max(rows, key=lambda x: int(x["r_count"]))             # 1e6 r values of one orbit
    tiny = [x for x in rows if int(x["r_count"]) < 1000]
    # bytes = orbits b + R p: b per orbit (9 doubles), p per r value (9 summary doubles and its table line), from the
    # 32-orbit runs and the 1-orbit run
    per_r_big = max(float(x["rows_bytes"]) / int(x["r_count"]) for x in big)          # 32 b + p
    per_r_one = float(at_scale["rows_bytes"]) / int(at_scale["r_count"])              # b + p
    b = (per_r_big - per_r_one) / 31
    p = max(0.0, per_r_one - b)
    t = max(float(x["bytes_gathered"]) / (int(x["r_count"]) - math.ceil(int(x["r_count"]) / int(x["ranks"])))
            for x in big)
    W = min(float(x["rows_bytes"]) / float(x["rows_seconds"]) for x in big)
    merge = float(at_scale["merge_seconds"]) / int(at_scale["r_count"])
    alone = sorted(float(x["root_seconds"]) - float(x["rows_seconds"]) for x in tiny)
    a = alone[len(alone) // 2]
    # (clamped at 0: with the per-r output written by the ranks, the 1e6-r run's rank 0 differs from the tiny runs'
    # by less than this shared machine's noise)
    tau = max(0.0, (float(at_scale["root_seconds"]) - float(at_scale["rows_seconds"]) - a) / int(at_scale["r_count"]))
    # c(P) = c_2 + ALPHA [n_tree (log2 P - 1) + n_pair (P - 2)]: c_2 the tiny write at P = 2 (no oversubscription
    # here), n_tree and n_pair the collectives per rank counted at the largest P measured
    at_2 = sorted(float(x["rows_seconds"]) for x in tiny if int(x["ranks"]) == 2)
    c2 = at_2[len(at_2) // 2]
    counts = collective_counts(d)
    P_counted = max(counts)
    # the overlays' bounds computed in shares before the run: rank 0's own share w / P of w seconds of one core.  Here
    # P ranks share this machine's cores, so a share of w / P CPU seconds takes w / min(P, cores) of wall time:
    # w = share x min(P, cores), the median over the tiny runs
    cores = os.cpu_count() or 1
    ws = sorted(float(x["share_seconds"]) * min(int(x["ranks"]), cores) for x in tiny if x.get("share_seconds"))
    w = ws[len(ws) // 2] if ws else 0.0
    return dict(b=b, p=p, t=t, W=W, merge=merge, c2=c2, n_tree=counts[P_counted]["tree"],
                n_pair=counts[P_counted]["pair"], P_counted=P_counted, counts=counts,
                tiny={int(x["ranks"]): float(x["rows_seconds"]) for x in tiny}, a=a, tau=tau, w=w)


def collective_counts(d):
    """Per ranks P: the collective calls per rank by class (calls_max summed over the functions) and the functions
    by calls (collectives.csv)."""
    counts = {}
    for x in read(f"{d}/collectives.csv"):
        c = counts.setdefault(int(x["ranks"]), {"tree": 0, "pair": 0, "functions": []})
        c[x["class"]] += int(x["calls_max"])
        c["functions"].append((int(x["calls_max"]), x["function"], x["class"]))
    return counts


def write_fixed(m, nodes):
    """c(P), the ranks' write's fixed cost on P = nodes ranks: c_2 and the counted collectives' latency beyond P = 2."""
    return m["c2"] + ALPHA * (m["n_tree"] * (math.log2(nodes) - 1) + m["n_pair"] * (nodes - 2))


def write_fixed_derived(m):
    """The write's fixed cost c(P): the measured write of the tiny result, the counted collectives, c(P)."""
    tiny = ", ".join(f"{m['tiny'][P]:.3f} s at P = {P}" for P in sorted(m["tiny"]))
    print(f"The ranks' write of the tiny result took {tiny}.  Only P = 2 is used: this machine has 2 cores, so at "
          f"P = 3 and 4 the ranks take turns on them and the longer write is their waiting, not the growth of the "
          f"collectives with P; that growth is taken from the collectives counted per rank times the assumed latency "
          f"ALPHA = {ALPHA * 1e6:g} us.\n")
    counts = m["counts"]
    by_P = "; ".join(f"P = {P}: {c['tree']} tree, {c['pair']} pair" for P, c in sorted(counts.items()))
    same = all((c["tree"], c["pair"]) == (m["n_tree"], m["n_pair"]) for c in counts.values())
    growth = "the same at every P" if same else f"they grow with P, and those at P = {m['P_counted']} are used"
    top = ", ".join(f"{f} {n} ({k})" for n, f, k in sorted(counts[m["P_counted"]]["functions"], reverse=True)[:6])
    print(f"Collective calls per rank (the largest count over the ranks; tree: log2 P rounds each, pair: P - 1 "
          f"messages each): {by_P}; {growth}.  The most called at P = {m['P_counted']}: {top}.  These are all of the "
          f"run's collectives, the write's and the few outside it.\n")
    print(f"Derived: c(P) = c_2 + ALPHA [n_tree (log2 P - 1) + n_pair (P - 2)] with c_2 = {m['c2']:.4f} s (the tiny "
          f"write at P = 2), n_tree = {m['n_tree']}, n_pair = {m['n_pair']} (counted at P = {m['P_counted']}): "
          f"c(16) = {write_fixed(m, 16):.4f} s, c(64) = {write_fixed(m, 64):.4f} s, "
          f"c(256) = {write_fixed(m, 256):.4f} s\n")


def shares_at(m, nodes):
    """The overlays' shares before the run on `nodes` ranks: w / P and the exchange's latency."""
    return m["w"] / nodes + ALPHA * math.log2(nodes)


def result_bytes_of(m, n_orbits):
    """What the ranks write: b per orbit and p per r value."""
    return n_orbits * m["b"] + TARGET["r"] * m["p"]


def launch_here(d):
    by = {}
    for x in read(f"{d}/launch.csv"):
        by.setdefault(int(x["ranks"]), []).append(float(x["wall_seconds"]))
    return ", ".join(f"P = {p}: {sorted(v)[len(v) // 2]:.2f} s" for p, v in sorted(by.items()))


def root_alone(m):
    """Rank 0 alone after the gather, the ranks' write apart: a + tau R."""
    return m["a"] + m["tau"] * TARGET["r"]


def parallel_cost(s, m, n_orbits, total_steps, nodes, cores, fs):
    compute = total_steps / (nodes * cores * s)
    sent = TARGET["r"] * m["t"]
    gather_t = sent * (nodes - 1) / nodes / BETA + 3 * (nodes - 1) * ALPHA
    merge_t = root_alone(m) + shares_at(m, nodes)  # rank 0 after the gather, and the shares before the run
    result_bytes = result_bytes_of(m, n_orbits)
    exchange = result_bytes / nodes / BETA  # each rank's share to its block's rank, over its link
    write_t = write_fixed(m, nodes) + exchange + result_bytes / min(fs, nodes * BETA)
    return compute, gather_t, merge_t, write_t


def parallel_projection(s, m, n_orbits, total_steps):
    """Now: the ranks write their rows; rank 0 receives the per-r summary only."""
    rows = []
    for fs in FS:
        for cores in (2, 64):
            for nodes in (16, 64, 256):
                compute, gather_t, merge_t, write_t = parallel_cost(s, m, n_orbits, total_steps, nodes, cores, fs)
                launch = 0.5 + 0.01 * nodes
                io = gather_t + merge_t + write_t
                mem = n_orbits / nodes * (RECORDER_BYTES + m["b"])
                rows.append(dict(design="ranks write", fs_gbs=fs / 1e9, nodes=nodes, cores_per_node=cores,
                                 compute_s=compute, gather_s=gather_t, merge_s=merge_t, write_s=write_t,
                                 launch_s=launch, wall_s=compute + io + launch, efficiency=compute / (compute + io),
                                 efficiency_launch=compute / (compute + io + launch), memory_per_rank_gb=mem / 1e9,
                                 memory_rank0_gb=(mem + 2 * TARGET["r"] * m["t"]) / 1e9))
    return rows


def fs_for(target, s, m, n_orbits, total_steps, nodes, cores):
    """The file system bandwidth at which the efficiency (launch apart) reaches `target` (bisection)."""
    lo, hi = 1e6, 1e15
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        c, g, mg, w = parallel_cost(s, m, n_orbits, total_steps, nodes, cores, mid)
        lo, hi = (lo, mid) if c / (c + g + mg + w) >= target else (mid, hi)
    return hi


def print_table(rows, merge="merge"):
    print(f"| file system | nodes x cores | compute | gather | {merge} | write | efficiency | with launch | "
          "memory per rank | rank 0 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['fs_gbs']:g} GB/s | {r['nodes']} x {r['cores_per_node']} | {r['compute_s']:.3g} s | "
              f"{r['gather_s']:.2g} s | {r['merge_s']:.2g} s | {r['write_s']:.2g} s | {r['efficiency']:.3f} | "
              f"{r['efficiency_launch']:.3f} | {r['memory_per_rank_gb']:.3g} GB | {r['memory_rank0_gb']:.3g} GB |")


def conclusion(s, m, n_orbits, total_steps):
    """The target (0.8 at 256 nodes x 64 cores) against the measured parts: the file system it needs, and what
    bounds the efficiency on any file system."""
    compute = total_steps / (256 * 64 * s)
    fixed = root_alone(m) + shares_at(m, 256) + write_fixed(m, 256)
    effs = []
    for fs in FS:
        c, g, mg, w = parallel_cost(s, m, n_orbits, total_steps, 256, 64, fs)
        effs.append(f"{c / (c + g + mg + w):.2f} at {fs / 1e9:g} GB/s")
    need = fs_for(0.8, s, m, n_orbits, total_steps, 256, 64)
    print(f"\nAt 256 nodes x 64 cores the job computes for {compute:.1f} s.  What does not depend on the file system "
          f"(rank 0 alone after the gather, {root_alone(m):.2f} s, the overlays' shares before the run, "
          f"{shares_at(m, 256):.3f} s, and the write's fixed cost c(256), {write_fixed(m, 256):.3f} s) takes "
          f"{fixed:.2f} s, "
          f"which bounds the efficiency at {compute / (compute + fixed):.2f} on any file system; the efficiency is "
          f"{', '.join(effs)}.")
    if need < 1e14:
        print(f"\nAn efficiency of 0.8 (launch apart) needs a file system of {need / 1e9:.0f} GB/s or more: the "
              f"{result_bytes_of(m, n_orbits) / 1e9:.0f} GB are written after the compute, not during it.")
    else:
        print("\nAn efficiency of 0.8 (launch apart) is out of reach for any file system at this job's size.")
    faster(s, m, n_orbits, total_steps, fixed)


def faster(s, m, n_orbits, total_steps, fixed):
    """The same target on faster cores: the compute shrinks with the per-core rate, the bytes and fixed costs do not,
    so the file system 0.8 needs grows.  The projection's rate is this machine's core; a cluster's may be faster."""
    parts = []
    for k in (2, 4):
        compute = total_steps / (256 * 64 * k * s)
        need = fs_for(0.8, k * s, m, n_orbits, total_steps, 256, 64)
        needs = f"needs {need / 1e9:.0f} GB/s" if need < 1e14 else "is out of reach"
        parts.append(f"at {k} s ({k * s:.2g} steps/s per core: {compute:.1f} s of compute) 0.8 {needs} "
                     f"(bound {compute / (compute + fixed):.2f})")
    print(f"\nThe compute rate is this machine's, s = {s:.3g} steps/s per core; on faster cores the compute is shorter "
          f"and the file system must be faster: {'; '.join(parts)}.")


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
    print(f"Projection: {TARGET['r']:.0e} r x {TARGET['ic']} orbits x ({TARGET['iterations']:.0e} + "
          f"{TARGET['transient']}) steps = {total_steps:.3g} steps.\n")
    m = rows_parameters(d)
    print("### Before: every rank's rows gathered to rank 0, which merges and writes\n")
    before = gathered_projection(s, b, merge_rate, n_orbits, total_steps, m)
    print_table(before, "merge and rank 0 alone")
    print("\n### Now: each rank writes its own rows (parallel HDF5); rank 0 receives the summary per r only\n")
    rows_measured(d)
    print(f"\nDerived: b = {m['b']:.1f} bytes per orbit (9 doubles), p = {m['p']:.0f} bytes per r value (its summary's "
          f"9 doubles and table line), t = {m['t']:.1f} bytes per r value sent to rank 0, "
          f"rank 0's merge {m['merge'] * 1e6:.2f} us per r value; "
          f"the overlays' shares before the run w / P with w = {m['w']:.2f} s; "
          f"rank 0 alone after the gather (its write apart) a + tau R with a = {m['a']:.2f} s, tau = "
          f"{m['tau'] * 1e6:.2f} us per r value ({root_alone(m):.1f} s at {TARGET['r']:.0e} r values); "
          f"the ranks' write here {m['W'] / 1e6:.0f} MB/s in all (one shared disk); launch here {launch_here(d)}\n")
    write_fixed_derived(m)
    result_bytes = result_bytes_of(m, n_orbits)
    print(f"Result {result_bytes / 1e9:.1f} GB written by the ranks; rank 0 receives "
          f"{TARGET['r'] * m['t'] / 1e6:.0f} MB.\n")
    now = parallel_projection(s, m, n_orbits, total_steps)
    print_table(now, "rank 0 alone, shares")
    conclusion(s, m, n_orbits, total_steps)
    with open(f"{d}/projection.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(now[0]))
        w.writeheader()
        for r in before + now:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
