#!/usr/bin/env python3
"""Draws the mean empirical measure of `btob measure` (log colour, support outlined) and each initial
condition's total-variation distance to it, with the convergence against N.
Usage: stats_measure.py DATA.h5 OUT.png"""
import os
import sys

import h5py
import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(src, dst):
    with h5py.File(src, "r") as f:
        m = f["mean_measure"][...]
        tv = f["tv_to_mean"][...]
        cn, ct = f["convergence_n"][...], f["convergence_tv"][...]
        ext = f["extent"][...]
        a = attrs(f)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.2), dpi=130, gridspec_kw={"width_ratios": [1.4, 1]})
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("white")
    pos = m[m > 0]
    im = ax.imshow(np.where(m > 0, m, np.nan).T, origin="lower", aspect="auto", extent=list(ext), cmap=cmap,
                   norm=mcolors.LogNorm(vmin=max(pos.min(), 1e-8) if pos.size else 1e-8, vmax=pos.max() if pos.size else 1),
                   interpolation="nearest")
    ax.contour(np.linspace(ext[0], ext[1], m.shape[0]), np.linspace(ext[2], ext[3], m.shape[1]), (m > 0).T.astype(float),
               levels=[0.5], colors="k", linewidths=0.4)
    if a["chart"] == "strip":
        ax.set_xlabel(r"$\arctan w_1$ (rad)")
        ax.set_ylabel(r"$w_2$ (dimensionless)")
    else:
        ax.set_xlabel(r"$\theta$ (rad)")
        ax.set_ylabel(r"$\varphi$ (rad)")
    fig.colorbar(im, ax=ax, pad=0.01).set_label("mass per bin (weights 1/N), support outlined")
    ax.set_title(f"mean empirical measure of {a['initial_conditions']} orbits", fontsize=9)
    bx.semilogy(np.arange(len(tv)), np.maximum(tv, 1e-17), "o", ms=3, label="each orbit vs the mean")
    bx.semilogy(cn, np.maximum(ct, 1e-17), "-", label="orbit 0: mu_N vs mu of the whole run (x = N)")
    bx.set_xscale("symlog", linthresh=32)
    bx.set_xlabel("initial condition index / N (map iterations)")
    bx.set_ylabel("total variation distance (1e-17: zero)")
    bx.legend(fontsize=8)
    bx.set_title(f"largest distance between two orbits' measures: {a['tv_max_pair']:.3g}", fontsize=9)
    fig.suptitle(f"Empirical measures at r = {a['r']}, grid {a['grid']}, {a['iterations']} iterations after {a['transient']}, "
                 f"{a['bins']}x{a['bins']} bins ({a['chart']} chart), double", fontsize=10)
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: stats_measure.py DATA.h5 OUT.png")
    main(*sys.argv[1:])
