#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Speed against accuracy of each precision and algorithm (`btob precision`).

Four panels, each against iterations per second: how long the symbol sequence agrees with a 256-digit run
(median over orbits) at each r; the final-state error; the Lyapunov exponent's error on periodic sinks; the
largest window (ab)^n(cb)^n resolved.
Usage: precision_tradeoff.py NAME.h5 OUT.png
Reads NAME.h5 alone (method names, r, iterations_per_second, agree_median and final_error_median [method, r],
lyapunov_error, lyapunov_error_near_neutral and window_n_max [method]; the attribute iterations); NAME.csv is the
same table.  The windows panel also draws the paper's Table B.1 (analyses/reference, shipped with the scripts).
"""
import csv
import math
import os


import plotlib  # noqa: E402  (main: the command line)
from plotlib import texts  # noqa: F401  (also selects the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402


def rows_of(f):
    """One dict per method, keyed as the CSV's columns (agree_median_r<r>, final_error_median_r<r>, ...); a value not
    measured for that method (trig: no Lyapunov error, no window test) is absent."""
    methods = texts(f, "method")
    rs = [f"{float(x):g}" for x in f["r"][()]]
    rate, agree, err = f["iterations_per_second"][()], f["agree_median"][()], f["final_error_median"][()]
    lyap, near, nmax = f["lyapunov_error"][()], f["lyapunov_error_near_neutral"][()], f["window_n_max"][()]
    rows = []
    for m, name in enumerate(methods):
        row = {"method": name, "iterations_per_second": float(rate[m])}
        for k, r in enumerate(rs):
            row[f"agree_median_r{r}"] = int(agree[m][k])
            row[f"final_error_median_r{r}"] = float(err[m][k])
        for key, v in (("lyapunov_error", lyap[m]), ("lyapunov_error_near_neutral", near[m])):
            if math.isfinite(float(v)):
                row[key] = float(v)
        if float(nmax[m]) >= 0:
            row["window_n_max"] = int(nmax[m])
        rows.append(row)
    return rs, rows


def draw(f):
    """The figure of an h5py-like f (the datasets `btob precision` writes)."""
    rs, rows = rows_of(f)
    iters = str(int(f.attrs["iterations"])) if "iterations" in f.attrs else "?"
    fig, axes = plt.subplots(2, 2, figsize=(15, 10.5), dpi=120)
    (ax, cx), (lx, bx) = axes
    markers = "os^Dv<>"
    for i, r in enumerate(rs):
        x = [row["iterations_per_second"] for row in rows]
        y = [max(1, row[f"agree_median_r{r}"]) for row in rows]
        ax.scatter(x, y, marker=markers[i % len(markers)], s=40, label=f"r = {r}", alpha=0.85)
        for k, (xi, yi, row) in enumerate(zip(x, y, rows)):
            if i == 0:  # labels of neighbouring methods staggered vertically (they overlapped at equal y)
                ax.annotate(row["method"], (xi, yi), textcoords="offset points", xytext=(5, 4 + 9 * (k % 3)),
                            fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axhline(int(iters) if iters.isdigit() else 1, color="#999999", ls=":", lw=1)
    ax.set_xlabel("map iterations per second (2 threads; trig/double: 1 thread)")
    ax.set_ylabel("iterations until the symbols differ from the 256-digit run\n(median over orbits; dotted: all agree)")
    ax.set_title(f"symbol agreement with MPFR 256 digits ({iters} iterations compared)", fontsize=9)
    ax.legend(fontsize=8)
    for i, r in enumerate(rs):
        key = f"final_error_median_r{r}"
        if key not in rows[0]:
            continue
        x = [float(row["iterations_per_second"]) for row in rows]
        y = [max(1e-20, float(row[key])) for row in rows]
        cx.scatter(x, y, marker=markers[i % len(markers)], s=40, label=f"r = {r}", alpha=0.85)
        if i == 1:
            for k, (xi, yi, row) in enumerate(zip(x, y, rows)):
                cx.annotate(row["method"], (xi, yi), textcoords="offset points", xytext=(5, 4 + 9 * (k % 3)),
                            fontsize=7)
    cx.set_xscale("log")
    cx.set_yscale("log")
    cx.set_xlabel("map iterations per second (2 threads; trig/double: 1 thread)")
    cx.set_ylabel("angle between final state and 256-digit run (rad, median)\n(1e-20: below double resolution)")
    cx.set_title(f"state error after {iters} iterations", fontsize=9)
    cx.legend(fontsize=8)
    # Lyapunov exponent error on the sinks 1133, 111333, 132312 (linear methods only).
    ly = [row for row in rows if "lyapunov_error" in row]
    floor = 1e-17
    lx.scatter([float(row["iterations_per_second"]) for row in ly],
               [max(floor, float(row["lyapunov_error"])) for row in ly], color="#9467bd", s=40,
               label="strongly contracting sinks (largest error)")
    # The weakly contracting sink 312^150 at r = 0.171599 (just above 3 - 2 sqrt 2), when the CSV has it.
    nn = [row for row in rows if "lyapunov_error_near_neutral" in row]
    if nn:
        lx.scatter([float(row["iterations_per_second"]) for row in nn],
                   [max(floor, float(row["lyapunov_error_near_neutral"])) for row in nn], color="#d62728", marker="x",
                   s=50, label="weak sink 312^150, r = 0.171599 (lambda1 = -0.0116)")
    for k, row in enumerate(ly):
        lx.annotate(row["method"], (float(row["iterations_per_second"]), max(floor, float(row["lyapunov_error"]))),
                    textcoords="offset points", xytext=(5, 4 + 9 * (k % 3)), fontsize=7)
    # In the legend, not as text on the line: the text overlapped the methods' labels at the floor.
    lx.axhline(1.1e-16, color="#999999", ls=":", lw=1, label="double resolution of the reported value")
    lx.legend(fontsize=7, loc="center right")
    lx.set_xscale("log")
    lx.set_yscale("log")
    lx.set_ylim(floor / 3, 1e-1)
    lx.set_xlabel("map iterations per second (2 threads; trig/double: 1 thread)")
    lx.set_ylabel("largest |lambda1 - exact| per iteration on the sinks\n(1e-17: below double resolution)")
    lx.set_title("Lyapunov exponent, weighted average: 1133 (r=0.15), 111333 (r=0.1), 132312 (r=0.5), 1e5 steps"
                 + ("\nx: 312^150 (r=0.171599), 4e5 steps" if nn else ""), fontsize=9)  # two lines: one was cut off
    # Windows: every method resolved every n tested, so a "largest n resolved" plot says nothing.  Instead: the
    # width of window n (Table B.1, 12 decimals, extrapolated ~ n^-3 beyond n = 100) against the spacing of
    # representable r near 7 - 4 sqrt(3) in each precision: where a precision must fail, and how far the test went.
    import numpy as np
    ref = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference", "windows_paper_table_B1.csv")
    with open(ref) as f:
        tb = [row for row in csv.DictReader(f) if row["upper_bound"]]
    nn = np.array([int(row["n"]) for row in tb])
    width = np.array([float(row["upper_bound"]) - float(row["lower_bound"]) for row in tb])
    good = (nn >= 20) & (width > 0)
    slope, icpt = np.polyfit(np.log(nn[good]), np.log(width[good]), 1)
    ne = np.logspace(np.log10(100), np.log10(5000), 60)
    bx.loglog(nn, width, "o", ms=3, color="#1f4fd6", label="window width, Table B.1 (12 decimals)")
    bx.loglog(ne, np.exp(icpt) * ne ** slope, "--", color="#1f4fd6", lw=1,
              label=f"fit n^{slope:.2f} on n >= 20, extrapolated")
    rc = 7 - 4 * np.sqrt(3)
    for name, eps, col in (("float", 2.0 ** -23, "#d62728"), ("double", 2.0 ** -52, "#2ca02c"),
                           ("long double", 2.0 ** -63, "#9467bd")):
        ulp = rc * eps
        bx.axhline(ulp, color=col, lw=1, ls=":")
        ncross = (ulp / np.exp(icpt)) ** (1 / slope)
        bx.text(2.2, ulp * 1.5, f"spacing of {name} numbers near r = 7-4*sqrt(3): {ulp:.1e}"
                + (f" (window narrower beyond n ~ {ncross:.0f})" if ncross < 5000 else ""), fontsize=7, color=col)
    ntest = max([row["window_n_max"] for row in rows if "window_n_max" in row] + [1])
    passed = [row["method"] for row in rows if row.get("window_n_max", -1) >= ntest]
    bx.axvspan(2, ntest, color="#dddddd", alpha=0.6, lw=0)
    bx.text(2.2, 1e-14, f"n <= {ntest} tested (8 orbits at the middle of each window):\n"
            f"resolved by all {len(passed)} linear methods (trig: not tested)", fontsize=7, va="bottom")
    bx.set_xlim(1.8, 5000)
    bx.set_ylim(1e-21, 1)
    bx.set_xlabel("n of the window (ab)^n(cb)^n")
    bx.set_ylabel("width of window n (dimensionless r)")
    bx.set_title("windows near 7-4*sqrt(3): width against the spacing of representable r", fontsize=9)
    bx.legend(fontsize=7, loc="upper right")
    fig.suptitle("btob: speed against accuracy, per precision and algorithm", fontsize=11)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
