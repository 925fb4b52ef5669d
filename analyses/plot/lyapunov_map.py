#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws a Lyapunov map (largest projective exponent of every orbit against r) from a `btob lyapunov-map` file.

Usage: lyapunov_map.py DATA.h5 OUT.png
Top: lambda1 of every orbit (dots), min/median/max per r, vertical lines at the thresholds 7-4sqrt3,
3-2sqrt2, 5-2sqrt6, 2^(2/3)-1 (red) and the window bounds (blue/grey, when the windows overlay was built).
Bottom: fraction of orbits whose lambda1 is clearly positive / zero / negative given its error bar.
Reads only the HDF5 file; writes OUT.png atomically (temporary file, then rename).
"""

import plotlib  # noqa: E402  (Agg for the command line; a Python session keeps its backend)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = {0: "#d62728", 1: "#1f4fd6", 2: "#9f9f9f"}


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    return v.decode() if isinstance(v, bytes) else v


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    r = f["r"][...]
    lam = f["lambda1"][...]
    mn, med, mx = f["min"][...], f["median"][...], f["max"][...]
    fp, fz, fn = f["frac_positive"][...], f["frac_zero"][...], f["frac_negative"][...]
    lines = f["overlay_lines"][...] if "overlay_lines" in f else np.zeros((0, 2))
    a = {k: attr(f, k) for k in f.attrs.keys()}
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(11, 7.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    rr = np.repeat(r, lam.shape[1])
    # min/max lines first and thin, the orbits' dots on top (they were hidden under the lines before).
    ax.plot(r, mn, color="#2ca02c", lw=0.4, alpha=0.8, label="min over initial conditions")
    ax.plot(r, mx, color="#ff7f0e", lw=0.4, alpha=0.8, label="max")
    ax.scatter(rr, lam.ravel(), s=1.5, c="#3a3a8c", alpha=0.5, linewidths=0, rasterized=True, label="each orbit", zorder=3)
    ax.plot(r, med, color="k", lw=0.8, label="median over initial conditions", zorder=4)
    ax.axhline(0, color="k", lw=0.4, ls=":")
    # Overlay lines thinned where they would merge (the window bounds accumulate at 7 - 4 sqrt(3)).
    px = 1300 / (r[-1] - r[0])
    kept, last = [], {}
    for x, c in sorted(lines.tolist(), key=lambda t: -t[0]):
        if int(c) in last and (last[int(c)] - x) * px < 3:
            continue
        last[int(c)] = x
        kept.append((x, c))
    for x, c in kept:
        for axis in (ax, bx):
            axis.axvline(x, color=COLOURS.get(int(c), "k"), lw=0.5, alpha=0.6)
    # The whole range of the data (the n = 2 sink's minimum included), padded.
    lo, hi = float(np.min(lam)), max(0.05, float(np.max(lam)))
    pad = 0.04 * (hi - lo)
    ax.set_ylim(lo - pad, hi + pad)
    if len(kept) < len(lines):
        ax.text(0.01, 0.02, f"vertical lines: {len(kept)} of {len(lines)} drawn (neighbours closer than 3 px skipped)",
                transform=ax.transAxes, fontsize=7)
    ax.set_ylabel(r"$\lambda_1$ (per map iteration, natural log)")
    ax.legend(loc="lower right", fontsize=8, markerscale=4)
    bx.stackplot(r, fn, fz, fp, colors=["#1f77b4", "#bbbbbb", "#d62728"], labels=["negative", "zero", "positive"], lw=0)
    bx.set_ylim(0, 1)
    bx.set_ylabel("fraction of orbits")
    bx.set_xlabel("restitution coefficient r (dimensionless)")
    bx.legend(loc="upper right", fontsize=7, ncol=3)
    title = a.get("title") or "Largest Lyapunov exponent of the b-to-b map"
    fig.suptitle(
        f"{title}\nr in [{float(a['r_min']):.4g}, {float(a['r_max']):.4g}], {int(a['r_count'])} values x grid "
        f"{a['grid']} ({int(a['initial_conditions'])} points), {int(a['iterations'])} iterations after "
        f"{int(a['transient'])} transient; red: thresholds, blue/grey: window bounds",
        fontsize=10,
    )
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw, usage=__doc__, dpi=130)
