#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws map iterations per second of bm_iterate (Google Benchmark JSON), with ratios to the scalar loop
of Appendix A.2 measured in the same run, and the estimated hardware limit of the double kernel.

Usage: benchmarks.py BM.json OUT.png
Google Benchmark's own JSON (analyses/benchmarks.sh), not a btob result: there is no HDF5 file to read.
"""
import json
import os
import sys

import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402

# An independent estimate from prototype measurements outside this repository (2-core Zen 5, double kernel): drawn
# only for that CPU (AMD family 26).
LIMIT_DOUBLE_2T = 1.2e10
LIMIT_CPU = ("AuthenticAMD", "26")
# core_clock times a chain of dependent 1-cycle adds; some cores fold such chains at rename (an Intel family 6
# model 207 reported 8.6-9.5 "GHz"), so a rate above this is no clock and is not shown.
MAX_PLAUSIBLE_GHZ = 6.5
# Our estimate (README, "Ceiling"): one map step of an 8-lane double vector is 12 vector instructions, 5 of
# them multiply-class.  Zen 5 (AMD family 26) has 4 full-width 512-bit FP pipes, 2 of which multiply:
# max(12/4, 5/2) = 3 cycles per vector, 8/3 lanes per cycle per core.  Zen 4 (family 25) splits a 512-bit
# multiply over its two 256-bit multiply pipes: 5 cycles per vector, 8/5 lanes per cycle.  Times the core
# clock measured in the same run (core_clock: a chain of dependent 1-cycle adds) and 2 cores.
LANES_PER_CYCLE = {("AuthenticAMD", "26"): 8 / 3, ("AuthenticAMD", "25"): 8 / 5}


def main(src, dst):
    with open(src) as f:
        data = json.load(f)
    rows = [b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
    # The clock: the median of core_clock's repetitions, and none when any repetition is implausible (a core that
    # folds the chain does so in some repetitions only: 6.0-9.5 "GHz" in one run).
    clocks = [b["GHz"] for b in rows if b["name"].startswith("core_clock") and "GHz" in b]
    clock = sorted(clocks)[len(clocks) // 2] if clocks and max(clocks) <= MAX_PLAUSIBLE_GHZ else None
    # With repetitions (analyses/benchmarks.sh interleaves them) each benchmark's median; in a fixed order, since the
    # interleaved repetitions come in random order: the scalar loops, the batched kernel, then Figure 4.1's pair.
    medians = [b for b in data["benchmarks"] if b.get("aggregate_name") == "median"]
    if medians:
        rows = [dict(b, name=b["run_name"]) for b in medians]
    family = ["scalar_loop", "batched", "fig41"]
    rows = sorted((b for b in rows if "items_per_second" in b),
                  key=lambda b: (next((i for i, f in enumerate(family) if b["name"].startswith(f)), len(family)),
                                 b["name"]))
    names = [b["name"].replace("/real_time", "") for b in rows]
    rate = [b["items_per_second"] for b in rows]
    base = next((b["items_per_second"] for b in rows if b["name"].startswith("scalar_loop/double")), None)
    fig, ax = plt.subplots(figsize=(10, 5.5), dpi=140)
    def colour(n):
        if n.startswith("scalar"):
            return "#7f7f7f"
        kind = n.split("/")[1]
        return {"double": "#1f77b4", "float": "#ff7f0e"}.get(kind, "#9467bd")
    colours = [colour(n) for n in names]
    bars = ax.barh(range(len(names)), rate, color=colours)
    ax.set_xscale("log")
    ax.set_yticks(range(len(names)))
    ax.set_yticklabels(names, fontsize=8)
    ax.invert_yaxis()
    for bar, v in zip(bars, rate):
        label = f"{v:.3g} it/s" + (f"  ({v / base:.2g}x scalar double)" if base else "")
        ax.text(v * 1.05, bar.get_y() + bar.get_height() / 2, label, va="center", fontsize=8)
    ctx = data.get("context", {})
    machine = (ctx.get("cpu_vendor"), ctx.get("cpu_family"))
    if machine == LIMIT_CPU:
        ax.axvline(LIMIT_DOUBLE_2T, color="#d62728", ls="--", lw=1)
        ax.text(LIMIT_DOUBLE_2T, len(names) - 0.5, " perf-notes limit\n double, 2 cores", color="#d62728", fontsize=7,
                va="bottom")
    lpc = LANES_PER_CYCLE.get(machine)
    if lpc and clock:
        ours = lpc * clock * 1e9 * 2
        ax.axvline(ours, color="#2ca02c", ls=":", lw=1)
        ax.text(ours, len(names) - 2.5, f"our estimate, double, 2 cores:\n{lpc:.2f} lanes/cycle x {clock:.2f} GHz x 2 ",
                color="#2ca02c", fontsize=7, va="bottom", ha="right")
    ax.set_xlabel("map iterations per second (log scale)")
    cpu = f"{ctx.get('cpu_model_name', 'CPU')} family {ctx.get('cpu_family', '?')}"
    clk = f"{clock:.2f} GHz measured" if clock else f"{ctx.get('mhz_per_cpu', '?')} MHz nominal"
    ax.set_title(f"btob iterator throughput, Figure 4.1 workload (r in [0.0717, 0.1717], Section 4 grid)\n"
                 f"{ctx.get('num_cpus', '?')} x {cpu}, {clk}, {ctx.get('date', '')[:16]}\n"
                 "names: route/precision/r values/iterations/threads[/MPFR digits]"
                 + (f"; medians of {medians[0].get('repetitions', '?')} interleaved repetitions" if medians else ""),
                 fontsize=9)
    ax.set_xlim(min(rate) / 2, max(max(rate), LIMIT_DOUBLE_2T if machine == LIMIT_CPU else 0) * 80)
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: benchmarks.py BM.json OUT.png")
    main(sys.argv[1], sys.argv[2])
