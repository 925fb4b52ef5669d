#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""analyses/benchmark_ratios.py against ratios known by construction, and on the committed results/benchmarks.

Synthetic run: every benchmark the script reads gets three repetitions (items/s a, 2a, 4a for a workload; b, 3b,
4b for a reference: medians 2a and 3b, means 7a/3 and 8b/3, so a mean in place of the median is caught) and its
median aggregate, in shuffled order as random interleaving writes them.  Expected: best 4a / 4b, median 2a / 3b,
band (a / 4b, 4a / b); the density rows compare times (1 / items): best (1/4a) / (1/4b), median 3b / 2a, band
(b / 4a, 4b / a).  Usage: benchmark_ratios_test.py REPO_ROOT
"""
import csv
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile

root = sys.argv[1]
script = os.path.join(root, "analyses", "benchmark_ratios.py")
sys.path.insert(0, os.path.join(root, "analyses"))
import benchmark_ratios as br  # noqa: E402  (the rows the script reads)

failures = 0


def check(ok, msg):
    global failures
    if not ok:
        failures += 1
        print("FAIL:", msg)


tmp = tempfile.mkdtemp()
try:
    rate = {}  # benchmark name -> base value a (items/s and 1/a ms)
    refs = {(prog, r.format(t=t)) for prog, w, r, *_ in br.ROWS for t in (1, 2)}
    for i, (prog, w, r, kind, goal, cmp) in enumerate(br.ROWS):
        for t in ((1, 2) if "{t}" in w else (None,)):
            rate.setdefault((prog, r.format(t=t)), 1000.0 * (t or 1))
            rate.setdefault((prog, w.format(t=t)), 1000.0 * (t or 1) / (i + 2))
    progs = {}
    rng = random.Random(1)
    for (prog, name), a in rate.items():
        rows = progs.setdefault(prog, [])
        full = name + "/real_time"
        factors = (1, 3, 4) if (prog, name) in refs else (1, 2, 4)
        for k, f in enumerate(factors):
            rows.append(dict(name=full, run_name=full, run_type="iteration", repetition_index=k,
                             items_per_second=a * f, real_time=1e3 / (a * f), time_unit="ms"))
        for agg, f in (("mean", sum(factors) / 3), ("median", factors[1])):
            rows.append(dict(name=full + "_" + agg, run_name=full, run_type="aggregate", aggregate_name=agg,
                             items_per_second=a * f, real_time=1e3 / (a * f), time_unit="ms"))
    for prog, rows in progs.items():
        rng.shuffle(rows)
        with open(os.path.join(tmp, prog + ".json"), "w") as f:
            json.dump({"context": {}, "benchmarks": rows}, f)
    out = subprocess.run([sys.executable, script, tmp], capture_output=True, text=True)
    check(out.returncode == 0, f"synthetic run failed: {out.stderr.strip()}")
    with open(os.path.join(tmp, "ratios.csv")) as f:
        got = list(csv.DictReader(f))
    check(len(got) == sum(2 if "{t}" in w else 1 for _, w, *_ in br.ROWS), f"{len(got)} rows")
    for g in got:
        a, b = rate[(g["program"], g["workload"])], rate[(g["program"], g["reference"])]
        if (g["program"], g["workload"]) in refs:  # map_float against map_double: both references' factors
            a_med = 3 * a
        else:
            a_med = 2 * a
        if g["compared"] == "rate":
            want = (a / b, a_med / (3 * b), a / (4 * b), 4 * a / b)
        else:
            want = (b / a, 3 * b / a_med, b / (4 * a), 4 * b / a)
        have = tuple(float(g[k]) for k in ("ratio_best", "ratio_median", "band_low", "band_high"))
        check(all(abs(h - w) <= 1e-3 * w for h, w in zip(have, want)), f"{g['workload']}: {have} != {want}")
        check(g["repetitions"] == "3", f"{g['workload']}: repetitions {g['repetitions']}")
    # A missing benchmark is an error naming it, and leaves no ratios.csv behind.
    os.remove(os.path.join(tmp, "ratios.csv"))
    with open(os.path.join(tmp, "bm_attractors.json")) as f:
        data = json.load(f)
    data["benchmarks"] = [b for b in data["benchmarks"] if not b["run_name"].startswith("classify/300/2")]
    with open(os.path.join(tmp, "bm_attractors.json"), "w") as f:
        json.dump(data, f)
    out = subprocess.run([sys.executable, script, tmp], capture_output=True, text=True)
    check(out.returncode != 0 and "classify/300/2" in out.stderr, f"missing benchmark not named: {out.stderr!r}")
    check(not os.path.exists(os.path.join(tmp, "ratios.csv")), "partial ratios.csv written")
    # The committed run (copied: the script writes ratios.csv beside its input).
    committed = os.path.join(root, "results", "benchmarks")
    for prog in sorted({p for p, *_ in br.ROWS}):
        shutil.copy(os.path.join(committed, prog + ".json"), tmp)
    out = subprocess.run([sys.executable, script, tmp], capture_output=True, text=True)
    check(out.returncode == 0, f"committed run: {out.stderr.strip()}")
    if os.path.exists(os.path.join(committed, "ratios.csv")):
        with open(os.path.join(committed, "ratios.csv")) as f, open(os.path.join(tmp, "ratios.csv")) as g:
            check(f.read() == g.read(), "results/benchmarks/ratios.csv is not what its JSONs give")
finally:
    shutil.rmtree(tmp)
print("ok" if failures == 0 else f"{failures} failure(s)")
sys.exit(1 if failures else 0)
