#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the empirical measures of a `btob measure` HDF5 file: one image per group of coinciding measures
(log colour, support outlined per group), their marginals, and the convergence against N.
Usage: stats_measure.py DATA.h5 OUT.png"""

import matplotlib

import plotlib  # noqa: E402,F401  (Agg for the command line; a Python session keeps its backend)
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    counts = f["group_counts"][...].astype(float)
    mu, mv = f["group_marginal_u"][...], f["group_marginal_v"][...]
    size = f["group_size"][...]
    tvmax = f["group_tv_max"][...]
    cn = f["convergence_n"][...]
    within, tofull = f["convergence_tv_within_group"][...], f["convergence_tv_to_full"][...]
    tv = f["tv_to_group_head"][...]
    ext = f["extent"][...]
    a = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    G, B = counts.shape[0], counts.shape[1]
    mass = counts / a["iterations"]
    strip = a["coords"] == "strip"
    xl = r"$\arctan w_1$ (rad)" if strip else r"$\theta$ (rad)"
    yl = r"$w_2$ (dimensionless)" if strip else r"$\varphi$ (rad)"
    fig, axs = plt.subplots(1, 3, figsize=(17, 5.2), dpi=120, gridspec_kw={"width_ratios": [1.35, 1, 1]})
    ax, bx, cx = axs
    total = mass.sum(axis=0) / G
    pos = total[total > 0]
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("white")
    im = ax.imshow(np.where(total > 0, total, np.nan).T, origin="lower", aspect="auto", extent=list(ext), cmap=cmap,
                   norm=mcolors.LogNorm(vmin=pos.min(), vmax=pos.max()), interpolation="nearest")
    xs = np.linspace(ext[0], ext[1], B + 1)
    ys = np.linspace(ext[2], ext[3], B + 1)
    xc, yc = 0.5 * (xs[1:] + xs[:-1]), 0.5 * (ys[1:] + ys[:-1])
    for g in range(G):
        sup = (mass[g] > 0).T.astype(float)
        if sup.sum() <= 8:  # atoms: mark the bins and write their mass beside them
            ii, jj = np.nonzero(mass[g])
            ax.plot(xc[ii], yc[jj], "s", mfc="none", mec=f"C{g % 10}", ms=9, mew=1.2,
                    label=f"group {g}: {size[g]} orbits, {int(sup.sum())} atoms")
            for i, j in zip(ii, jj):
                ax.annotate(f"{mass[g][i, j]:.3g}", (xc[i], yc[j]), textcoords="offset points",
                            xytext=(8 if xc[i] < 0.5 * (ext[0] + ext[1]) else -8, -4 if yc[j] > 0 else 10),
                            ha="left" if xc[i] < 0.5 * (ext[0] + ext[1]) else "right", fontsize=7, color=f"C{g % 10}")
        else:
            ax.contour(xc, yc, sup, levels=[0.5], colors=[f"C{g % 10}"], linewidths=0.6)
            ax.plot([], [], color=f"C{g % 10}", label=f"group {g}: {size[g]} orbits, support {int(sup.sum())} bins")
    ax.set_xlabel(xl)
    ax.set_ylabel(yl)
    # Pad the axes: atoms sit on the strip's edges (w2 = +-1, arctan w1 near +-pi/2).
    dx, dy = 0.04 * (ext[1] - ext[0]), 0.05 * (ext[3] - ext[2])
    ax.set_xlim(ext[0] - dx, ext[1] + dx)
    ax.set_ylim(ext[2] - dy, ext[3] + dy)
    # Legend below the axes: inside it hid an atom.
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    if pos.max() / pos.min() >= 2:
        fig.colorbar(im, ax=ax, pad=0.01).set_label("mass per bin (weights 1/N, mean over groups)")
    else:  # a colour bar spanning a factor < 2 says nothing: the masses are written beside the atoms
        ax.text(0.01, 0.99, f"every occupied bin carries mass {pos.min():.3g} to {pos.max():.3g}",
                transform=ax.transAxes, fontsize=7, va="top")
    ax.set_title(f"empirical measures, {B}x{B} bins; support outlined per group", fontsize=9)
    xu = np.linspace(ext[0], ext[1], B)
    xv = np.linspace(ext[2], ext[3], B)
    for g in range(G):
        bx.step(xu, mu[g], where="mid", lw=0.8, color=f"C{g % 10}", label=f"group {g}: u marginal")
        bx.step(xv, mv[g], where="mid", lw=0.8, ls="--", color=f"C{g % 10}", label=f"group {g}: v marginal")
    if max((m > 0).sum() for m in mass) > 8:
        bx.set_yscale("log")  # spread measures: many decades; atoms: linear, so equal masses look equal
    bx.set_xlabel(f"u = {xl} (solid), v = {yl} (dashed)")
    bx.set_ylabel("mass per bin")
    bx.set_title("1-D marginals of each group's first measure", fontsize=9)
    bx.legend(fontsize=6, ncol=2)
    for g in range(G):
        if size[g] > 1:
            cx.loglog(cn, np.maximum(within[:, g], 1e-7), "o-", ms=3, color=f"C{g % 10}",
                      label=f"group {g}: max TV between members at N")
        cx.loglog(cn, np.maximum(tofull[:, g], 1e-7), "s:", ms=3, color=f"C{g % 10}",
                  label=f"group {g}: TV(mu_N, mu at N = {a['iterations']})")
    cx.loglog(cn, 1 / np.sqrt(cn), "k--", lw=0.6, label=r"$N^{-1/2}$")
    cx.axhline(1e-3, color="grey", lw=0.6, ls="-.", label="1e-3")
    cx.set_xlabel("N (map iterations after the transient)")
    cx.set_ylabel("total variation distance (1e-7 stands for 0)")
    cx.set_title(f"convergence; largest TV within a group at N = {a['iterations']}: {a['tv_max_within_groups']:.2g}",
                 fontsize=9)
    cx.legend(fontsize=6)
    fig.suptitle(f"Empirical measures at r = {a['r']}, grid {a['grid']} ({a['initial_conditions']} initial conditions, "
                 f"{G} group(s) at TV < {a['tv_same']}), N = {a['iterations']} after transient {a['transient']}, "
                 f"{a['coords']} coordinates, double", fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
