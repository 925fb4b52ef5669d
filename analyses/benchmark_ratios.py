#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The speed ratios from one benchmark run: each workload against the plain kernel measured in the same program.

Usage: analyses/benchmark_ratios.py [DIR]     (DIR = results/benchmarks; writes DIR/ratios.csv, prints a Markdown table)

analyses/benchmarks.sh runs bm_iterate, bm_lyapunov and bm_attractors with repetitions in random interleaving, and
bm_lyapunov and bm_attractors carry the plain kernel as `plain_reference` (benchmarks/plain_reference.hpp): every
ratio here divides two values of the same program, whose repetitions alternated in the same minutes.  On a shared
machine noise only adds time (other tenants take the core: the same binary ran at 283 and 550 ms in one run), so the
first ratio is of the two benchmarks' best repetitions, the code's speed when undisturbed; then the ratio of
medians, and the band: the ratio's range over the repetitions (the slowest workload repetition against the fastest
reference one, and the reverse), how far the noise could move it.  The goal is judged on the best repetitions.  A
JSON without repetitions (an older run) gives its single values and a band of one point.
"""
import csv
import json
import math
import os
import sys
import tempfile

# (program, workload, reference, what is compared, goal, direction): rate ratios are workload items/s over the
# reference's; "time" ratios are the workload's time over the reference's (the density image's cost).
ROWS = [
    ("bm_lyapunov", "map_double/500/10000/{t}", "plain_reference/1000/5000/{t}", "rate", 1 / 4, ">="),
    ("bm_lyapunov", "map_float/500/10000/{t}", "map_double/500/10000/{t}", "rate", 1.6, ">="),
    ("bm_lyapunov", "map_recorder/double/500/10000/{t}", "plain_reference/1000/5000/{t}", "rate", None, ""),
    ("bm_lyapunov", "clv_batched/20/{t}", "plain_reference/1000/5000/{t}", "rate", 1 / 4, ">="),
    ("bm_attractors", "classify/102/{t}", "plain_reference/1000/5000/{t}", "rate", 1 / 4, ">="),
    ("bm_attractors", "classify/300/{t}", "plain_reference/1000/5000/{t}", "rate", 1 / 4, ">="),
    ("bm_attractors", "pass2_fused/300/64/{t}", "plain_reference/1000/5000/{t}", "rate", None, ""),
    ("bm_attractors", "pass1_batched/64", "plain_reference/1000/5000/1", "rate", None, ""),
    ("bm_iterate", "fig41_density/double/5000/5000/{t}", "fig41_plain/double/5000/5000/{t}", "time", 1.10, "<="),
    ("bm_iterate", "fig41_density_w2/double/5000/5000/1", "fig41_plain/double/5000/5000/1", "time", None, ""),
]


def key(name):
    """A benchmark's name without Google Benchmark's suffixes (/real_time, /iterations:N, _median ...)."""
    parts = [p for p in name.split("/") if p != "real_time" and not p.startswith("iterations:")]
    return "/".join(parts)


def load(path):
    """name -> (median, [repetition values]) of items/s and of real time, from one program's JSON."""
    with open(path) as f:
        data = json.load(f)
    reps, medians = {}, {}
    for b in data["benchmarks"]:
        name = key(b.get("run_name", b["name"]))
        if b.get("run_type", "iteration") == "iteration":
            reps.setdefault(name, []).append((b.get("items_per_second", math.nan), b["real_time"]))
        elif b.get("aggregate_name") == "median":
            medians[name] = (b.get("items_per_second", math.nan), b["real_time"])
    out = {}
    for name, values in reps.items():
        if name not in medians:  # no repetitions: the single run is its own median
            s = sorted(values)
            medians[name] = s[len(s) // 2]
        out[name] = (medians[name], values)
    return out


def ratio(w, r, kind):
    """Ratios of workload w against reference r (kind: rate or time): of the best repetitions (highest rate, shortest
    time), of the medians, and the band (low, high) over all repetitions."""
    idx = 0 if kind == "rate" else 1
    wm, wr = w[0][idx], [v[idx] for v in w[1]]
    rm, rr = r[0][idx], [v[idx] for v in r[1]]
    best = max(wr) / max(rr) if kind == "rate" else min(wr) / min(rr)
    return best, wm / rm, min(wr) / max(rr), max(wr) / min(rr)


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "results/benchmarks"
    programs = {}
    for prog in sorted({row[0] for row in ROWS}):
        p = os.path.join(d, prog + ".json")
        if not os.path.exists(p):
            sys.exit(f"benchmark_ratios: {p} not found (run analyses/benchmarks.sh first)")
        programs[prog] = load(p)
    out = []
    for prog, wname, rname, kind, goal, cmp in ROWS:
        for t in ((1, 2) if "{t}" in wname else (None,)):
            w, r = wname.format(t=t), rname.format(t=t)
            if w not in programs[prog] or r not in programs[prog]:
                sys.exit(f"benchmark_ratios: {prog}.json lacks {w if w not in programs[prog] else r}")
            best, med, lo, hi = ratio(programs[prog][w], programs[prog][r], kind)
            if not all(math.isfinite(v) and v > 0 for v in (best, med, lo, hi)):
                sys.exit(f"benchmark_ratios: {prog} {w} / {r}: no finite positive ratio (items/s missing?)")
            met = "" if goal is None else ("yes" if (best >= goal if cmp == ">=" else best <= goal) else "no")
            out.append(dict(program=prog, workload=w, reference=r, compared=kind, ratio_best=f"{best:.4g}",
                            ratio_median=f"{med:.4g}", band_low=f"{lo:.4g}", band_high=f"{hi:.4g}",
                            repetitions=min(len(programs[prog][w][1]), len(programs[prog][r][1])),
                            goal="" if goal is None else f"{cmp} {goal:.4g}", goal_met=met))
    fd, tmp = tempfile.mkstemp(dir=d, suffix=".tmp")
    with os.fdopen(fd, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(out[0].keys()))
        wr.writeheader()
        wr.writerows(out)
    os.replace(tmp, os.path.join(d, "ratios.csv"))
    print("| workload | against | ratio of the best repetitions | of the medians | band over repetitions | goal |")
    print("|---|---|---|---|---|---|")
    for o in out:
        def fmt(v):
            v = float(v)
            return f"1/{1 / v:.2f}" if o["compared"] == "rate" and v < 1 else f"{v:.3g}"
        what = "time" if o["compared"] == "time" else "rate"
        goal = f"{o['goal']} ({o['goal_met']})" if o["goal"] else ""
        print(f"| `{o['workload']}` | `{o['reference']}` ({what}) | {fmt(o['ratio_best'])} | {fmt(o['ratio_median'])} "
              f"| {fmt(o['band_low'])} .. {fmt(o['band_high'])} | {goal} |")


if __name__ == "__main__":
    main()
