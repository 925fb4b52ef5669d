#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Precision study of the window lower bounds: correct decimals and time per bound against n.

Usage: windows_precision.py NAME.h5 OUT.png
Reads NAME.h5 alone (written by `btob windows precision`, NAME = precision by default): n, abs_error and seconds
(rows x n) and the rows' precision and route (string datasets); NAME.csv is the same table.
"""
import math


import plotlib  # noqa: E402  (main: the command line)
from plotlib import texts
import matplotlib.pyplot as plt  # noqa: E402


def draw(f):
    """The figure of an h5py-like f (the datasets `btob windows precision` writes)."""
    n_all = [int(x) for x in f["n"][()]]
    abs_error, seconds = f["abs_error"][()], f["seconds"][()]
    series = {}
    for i, key in enumerate(zip(texts(f, "precision"), texts(f, "route"))):
        for j, n in enumerate(n_all):
            err = float(abs_error[i][j])
            # Correct decimals: -log10 |error|; a failed bound (NaN) or an error >= 1 counts as 0 decimals.
            dec = 0.0 if not math.isfinite(err) or err >= 1 else (60.0 if err == 0 else -math.log10(err))
            series.setdefault(key, ([], [], []))
            series[key][0].append(n)
            series[key][1].append(min(dec, 60.0))
            series[key][2].append(float(seconds[i][j]))
    precisions = []
    for p, _ in series:
        if p not in precisions:
            precisions.append(p)
    colours = dict(zip(precisions, ["tab:grey", "tab:blue", "tab:green", "tab:orange", "tab:red", "tab:purple"]))
    ns = n_all
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 6))
    for (p, route), (n, dec, sec) in series.items():
        style = "-" if route == "matrix" else "--"
        label = f"{p}, {route}"
        ax1.plot(n, dec, style, color=colours[p], label=label, lw=1.4)
        # Running median over 9 consecutive n: toms748 needs 8..30 evaluations depending on n, which
        # makes single timings jump by 10x; the median shows the trend.
        med = [sorted(sec[max(0, i - 4): i + 5])[len(sec[max(0, i - 4): i + 5]) // 2] for i in range(len(sec))]
        ax2.semilogy(n, med, style, color=colours[p], label=label, lw=1.2)
    ax1.axhline(12, color="black", lw=0.8, ls=":")
    ax1.text(min(ns), 12.5, "12 decimals (Table B.1)", fontsize=8)
    ax1.axhline(40, color="black", lw=0.5, ls=":")
    ax1.text(min(ns), 40.5, "reference: 40 certified decimals (errors below are not resolved)", fontsize=7)
    ax1.set_xlabel("n (pattern $(ab)^n(cb)^n$)")
    ax1.set_ylabel("correct decimals of the lower bound  ($-\\log_{10}|r_T - r^*|$)")
    ax1.set_ylim(0, 48)
    ax1.set_title("accuracy per scalar type (solid: matrix powers, dashed: Horner on $Q_n$)", fontsize=10)
    ax2.set_xlabel("n")
    ax2.set_ylabel("time per bound (s, running median over 9 n)")
    ax2.set_title("cost of one bound (toms748 root finding, 1 thread)", fontsize=10)
    fig.suptitle(
        f"Window lower bounds r*(n) = smallest positive root of $Q_n$, n = {min(ns)}..{max(ns)}: "
        "float, double, long double, float128, MPFR vs the certified 40-decimal value",
        fontsize=11,
    )
    handles, labels = ax1.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.1, 1, 0.95))
    return fig


if __name__ == "__main__":
    plotlib.main(draw, dpi=130)
