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
LIMIT_DOUBLE_2T = 1.2e10  # ../shared/perf-notes.md (full-width 512-bit pipes)
# README "Speed": Zen 4 runs a 512-bit FMA on both 256-bit FMA pipes: 5 multiply-class instructions per 8-lane
# step -> 5 cycles, 1.6 lanes/cycle/core, 8.3e9 on 2 cores at 2.6 GHz.
ZEN4_DOUBLE_2T = 8.3e9


def main(src, dst):
    with open(src) as f:
        data = json.load(f)
    rows = [b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
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
    ax.axvline(LIMIT_DOUBLE_2T, color="#d62728", ls="--", lw=1)
    ax.text(LIMIT_DOUBLE_2T, len(names) - 0.5, " perf-notes limit", color="#d62728", fontsize=7, va="bottom")
    ax.axvline(ZEN4_DOUBLE_2T, color="#2ca02c", ls=":", lw=1)
    ax.text(ZEN4_DOUBLE_2T, len(names) - 1.5, " Zen 4 limit (README)", color="#2ca02c", fontsize=7, va="bottom", ha="right")
    ax.set_xlabel("map iterations per second (log scale)")
    ctx = data.get("context", {})
    ax.set_title(f"btob iterator throughput, Figure 4.1 workload (r in [0.0717, 0.1717], Section 4 grid)\n"
                 f"{ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, {ctx.get('date', '')}; "
                 "names: route/precision/r values/iterations/threads[/MPFR digits]", fontsize=9)
    ax.set_xlim(min(rate) / 2, max(max(rate), LIMIT_DOUBLE_2T) * 40)
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: benchmarks.py BM.json OUT.png")
    main(sys.argv[1], sys.argv[2])
