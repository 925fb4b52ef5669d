#!/usr/bin/env python3
"""Draws map iterations per second of bm_iterate (Google Benchmark JSON), with ratios to the scalar loop
of Appendix A.2 measured in the same run, and the estimated hardware limit of the double kernel.

Usage: benchmarks.py BM.json OUT.png
"""
import json
import os
import sys

import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402

# Estimated ceiling of the double kernel on 2 cores (README, "Speed"): 7 FMA-pipe operations per
# 8-lane vector-step on 2 FMA pipes per core -> 2.3 lanes/cycle/core; at 2.6 GHz, 1.2e10 per 2 cores.
LIMIT_DOUBLE_2T = 1.2e10


def main(src, dst):
    with open(src) as f:
        data = json.load(f)
    rows = [b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
    names = [b["name"].replace("/real_time", "") for b in rows]
    rate = [b["items_per_second"] for b in rows]
    base = next((b["items_per_second"] for b in rows if b["name"].startswith("scalar_loop/double")), None)
    fig, ax = plt.subplots(figsize=(10, 5.5), dpi=140)
    colours = ["#7f7f7f" if n.startswith("scalar") else ("#1f77b4" if "double" in n else "#ff7f0e") for n in names]
    bars = ax.barh(range(len(names)), rate, color=colours)
    ax.set_xscale("log")
    ax.set_yticks(range(len(names)))
    ax.set_yticklabels([n.replace("/5000", " x5000 it").replace("/1000", " 1000 r").replace("/50", " 50 r")
                        .replace("/5000 x5000 it", "") for n in names], fontsize=8)
    ax.invert_yaxis()
    for bar, v in zip(bars, rate):
        label = f"{v:.3g} it/s" + (f"  ({v / base:.0f}x scalar)" if base else "")
        ax.text(v * 1.05, bar.get_y() + bar.get_height() / 2, label, va="center", fontsize=8)
    ax.axvline(LIMIT_DOUBLE_2T, color="#d62728", ls="--", lw=1)
    ax.text(LIMIT_DOUBLE_2T, len(names) - 0.5, " est. limit, double, 2 threads", color="#d62728", fontsize=8, va="bottom")
    ax.set_xlabel("map iterations per second (log scale)")
    ctx = data.get("context", {})
    ax.set_title(f"btob iterator throughput, Figure 4.1 workload (r in [0.0717, 0.1717], Section 4 grid)\n"
                 f"{ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, {ctx.get('date', '')}; "
                 "suffix /1 or /2 = threads", fontsize=9)
    ax.set_xlim(min(rate) / 2, max(max(rate), LIMIT_DOUBLE_2T) * 8)
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: benchmarks.py BM.json OUT.png")
    main(sys.argv[1], sys.argv[2])
