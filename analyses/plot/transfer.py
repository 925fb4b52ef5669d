# SPDX-License-Identifier: GPL-3.0-or-later
"""Ulam's transfer operator at one r: invariant density (Lebesgue projection), components, the sign structure of
the leading real eigenvector below 1, and the spectrum in the complex plane; the basins from the Ulam graph when the
request names attractors.  Usage: transfer.py H5 PNG.  Reads only the HDF5 file (the spectrum is its eig_re, eig_im
and eig_block); a run without a spectrum (--eigenvalues 0) gets the basins' two panels alone."""
import sys

import h5py
import numpy as np

from plotlib import attrs, save_atomic

import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm, ListedColormap


def basins_only(h5path, png):
    """A run without a spectrum: the attractor of largest absorption probability and that probability."""
    with h5py.File(h5path, "r") as f:
        a = attrs(f)
        cyc = f["cycle_points"][...] if "cycle_points" in f else np.zeros((0, 2))
        basin = f["basin"][...]
        basin_p = f["basin_probability"][...]
        basin_f = f["basin_fraction"][...]
    n1, n2 = int(a["n1"]), int(a["n2"])
    ext = [a["lo1"], a["hi1"], a["lo2"], a["hi2"]]
    strip = a["domain"] == "strip"
    fig, ax = plt.subplots(1, 2, figsize=(14, 5.8), squeeze=False)
    basin_panels(fig, ax[0, 0], ax[0, 1], a, basin, basin_p, basin_f, cyc, ext, strip)
    fig.suptitle(f"Basins from the Ulam graph of P_r, r = {a['r']}: {n1}x{n2} boxes ({a['domain']}), {a['samples']} "
                 f"samples per box (no spectrum: --eigenvalues 0)")
    fig.tight_layout(rect=(0, BASIN_LEGEND_ROOM, 1, 1))
    save_atomic(fig, png)


# The basins' legend goes below the panels (inside the basin image it covered a corner of it): the figure's bottom
# fraction kept free for it.
BASIN_LEGEND_ROOM = 0.07


def basin_panels(fig, axb, axp, a, basin, basin_p, basin_f, cyc, ext, strip):
    """(e) the attractor of largest absorption probability of every box; (f) that probability."""
    nb = len(basin_f)
    names = [str(a[f"basin_{k + 1}"]) for k in range(nb)]
    colours = [plt.cm.tab10(k % 10) for k in range(nb)]
    bmap = ListedColormap(["#f0f0f0"] + colours)
    axb.imshow(basin.T, origin="lower", extent=ext, aspect="auto", cmap=bmap, vmin=-0.5, vmax=nb + 0.5,
               interpolation="nearest")
    handles = [axb.plot([], [], "s", color=colours[k], label=f"{names[k]}: Lebesgue {basin_f[k]:.4f}")[0]
               for k in range(nb)]
    fig.legend(handles=handles, loc="lower center", ncol=min(nb, 4), fontsize=8, frameon=False,
               title="basins (the attractor of largest absorption probability): absorbed by", title_fontsize=8)
    axb.set_title(f"basins from the Ulam graph (unabsorbed {a['basin_unabsorbed']:.1e})")
    im5 = axp.imshow(basin_p.T, origin="lower", extent=ext, aspect="auto", cmap="viridis", vmin=0, vmax=1,
                     interpolation="nearest")
    fig.colorbar(im5, ax=axp, label="largest absorption probability")
    axp.set_title("certainty of the basin (< 1: within Ulam's blur of a boundary)")
    for axx in (axb, axp):
        axx.set_xlabel("atan(w1) (rad)" if strip else "theta (rad)")
        axx.set_ylabel("w2" if strip else "phi (rad)")
        if len(cyc):
            axx.plot(cyc[:, 0], cyc[:, 1], "o", mfc="none", mec="tab:red", ms=7, mew=1.0)
    if strip:
        # the lines w1 = +-2 bounding the Lebesgue rectangle of the fractions
        w1r = [float(x) for x in str(a["w1-range"]).split(",")]
        for axx in (axb, axp):
            for w in w1r:
                axx.axvline(np.arctan(w), color="k", lw=0.6, ls="--")


def main(h5path, png):
    with h5py.File(h5path, "r") as f:
        if "eig_re" not in f:
            return basins_only(h5path, png)
        a = attrs(f)
        re, im, block = f["eig_re"][...], f["eig_im"][...], f["eig_block"][...]
        dens = f["density"][...]
        second = f["second"][...]
        comp = f["component"][...]
        leb = f["lebesgue"][...]
        cyc = f["cycle_points"][...] if "cycle_points" in f else np.zeros((0, 2))
        basin = f["basin"][...] if "basin" in f else None
        basin_p = f["basin_probability"][...] if "basin" in f else None
        basin_f = f["basin_fraction"][...] if "basin" in f else None
    n1, n2 = int(a["n1"]), int(a["n2"])
    ext = [a["lo1"], a["hi1"], a["lo2"], a["hi2"]]
    strip = a["domain"] == "strip"
    xl = "atan(w1) (rad)" if strip else "theta (rad)"
    yl = "w2" if strip else "phi (rad)"
    area = (a["hi1"] - a["lo1"]) * (a["hi2"] - a["lo2"]) / (n1 * n2)
    nb = 0 if basin is None else len(basin_f)
    fig, ax = plt.subplots(2, 3 if nb else 2, figsize=(18 if nb else 12, 10.5), squeeze=False)
    # (a) density (mass per unit chart area), log scale
    d = dens / area
    pos = d[d > 0]
    im0 = ax[0, 0].imshow(np.where(d > 0, d, np.nan).T, origin="lower", extent=ext, aspect="auto", cmap="magma",
                          norm=LogNorm(vmin=max(pos.min(), pos.max() * 1e-8), vmax=pos.max()), interpolation="nearest")
    fig.colorbar(im0, ax=ax[0, 0], label="density (mass per unit chart area)")
    ax[0, 0].set_title("invariant density: Lebesgue projected on the components")
    if 0 < len(pos) < 5000:
        # A density on a few boxes (a sink's) would be invisible pixels: its boxes drawn as markers too.
        i1, i2 = np.nonzero(d > 0)
        c1 = a["lo1"] + (i1 + 0.5) * (a["hi1"] - a["lo1"]) / n1
        c2 = a["lo2"] + (i2 + 0.5) * (a["hi2"] - a["lo2"]) / n2
        ax[0, 0].scatter(c1, c2, c=d[i1, i2], cmap="magma", norm=im0.norm, s=10, marker="s",
                         label=f"the {len(pos)} boxes with mass (enlarged)")
    # (b) components
    k = int(comp.max())
    cmap = ListedColormap(["#f0f0f0"] + [plt.cm.tab10(i % 10) for i in range(max(k, 1))])
    ax[0, 1].imshow(comp.T, origin="lower", extent=ext, aspect="auto", cmap=cmap, vmin=-0.5, vmax=k + 0.5,
                    interpolation="nearest")
    if 0 < np.count_nonzero(comp) < 5000:  # a few boxes (a sink's class): drawn as enlarged markers too
        j1, j2 = np.nonzero(comp)
        ax[0, 1].scatter(a["lo1"] + (j1 + 0.5) * (a["hi1"] - a["lo1"]) / n1,
                         a["lo2"] + (j2 + 0.5) * (a["hi2"] - a["lo2"]) / n2, c=comp[j1, j2], cmap=cmap,
                         vmin=-0.5, vmax=k + 0.5, s=10, marker="s")
    for i in range(k):
        ax[0, 1].plot([], [], "s", color=plt.cm.tab10(i % 10), label=f"component {i + 1}: Lebesgue {leb[i]:.3f}")
    if k:
        ax[0, 1].legend(loc="upper right", fontsize=8)
    ncl = int(a["closed_classes"])
    classes = f"{ncl} closed class" + ("" if ncl == 1 else "es")
    if k > ncl:  # PCCA+ split the closed classes (or the transient block) into almost-invariant components
        ax[0, 1].set_title(f"{k} components: {classes} split by PCCA+\ninto almost-invariant sets; grey: transient")
    else:
        ax[0, 1].set_title(f"components: {classes}; grey: transient")
    for axx in (ax[0, 0], ax[0, 1]):
        if len(cyc):
            axx.plot(cyc[:, 0], cyc[:, 1], "o", mfc="none", mec="tab:cyan", ms=9, mew=1.2,
                     label="exact cycle points (--cycle)")
    if len(cyc):
        ax[0, 0].legend(loc="lower right", fontsize=8)
    # (c) sign structure of the next eigenvector
    s = second
    v = np.abs(s).max() or 1
    im2 = ax[1, 0].imshow(np.sign(s).T * np.abs(s).T ** 0.25, origin="lower", extent=ext, aspect="auto", cmap="RdBu_r",
                          vmin=-1, vmax=1, interpolation="nearest")
    fig.colorbar(im2, ax=ax[1, 0], label="sign(v) |v|^(1/4), v scaled to max |v| = 1")
    if a["second_value"] > 0:
        ax[1, 0].set_title(f"eigenvector of lambda = {a['second_value']:.6f}: + mass {a['second_positive_mass']:.3f}, "
                           f"- mass {a['second_negative_mass']:.3f}")
    else:
        ax[1, 0].set_title("no real eigenvalue in (0, 1) among the leading ones")
    for axx in (ax[0, 0], ax[0, 1], ax[1, 0]):
        axx.set_xlabel(xl)
        axx.set_ylabel(yl)
    # (d) spectrum
    t = np.linspace(0, 2 * np.pi, 400)
    ax[1, 1].plot(np.cos(t), np.sin(t), color="0.6", lw=0.8, label="unit circle")
    beta = float(a.get("p2_beta", float("nan")))
    if np.isfinite(beta):
        kk = np.arange(-12, 13)
        ax[1, 1].plot(np.cos(kk * beta), np.sin(kk * beta), "x", color="tab:green", ms=7,
                      label="exp(i k beta), |k| <= 12, cos beta = -(1-r)^2/(4r)")
    ax[1, 1].scatter(re[block == 0], im[block == 0], s=18, color="tab:blue", label="transient block")
    ax[1, 1].scatter(re[block > 0], im[block > 0], s=30, color="tab:red", marker="D", label="closed classes")
    ax[1, 1].set_aspect("equal")
    ax[1, 1].set_xlim(-1.1, 1.1)
    ax[1, 1].set_ylim(-1.1, 1.1)
    ax[1, 1].set_xlabel("Re lambda")
    ax[1, 1].set_ylabel("Im lambda")
    ax[1, 1].legend(loc="lower left", fontsize=8)
    ax[1, 1].set_title(f"{len(re)} leading eigenvalues; {a['near_one_count']} within {a['near-one']} of 1")
    if nb:
        basin_panels(fig, ax[0, 2], ax[1, 2], a, basin, basin_p, basin_f, cyc, ext, strip)
    fig.suptitle(f"Ulam transfer operator of P_r, r = {a['r']}: {n1}x{n2} boxes ({a['domain']}), {a['samples']} samples "
                 f"per box\nTV to the empirical measure {a['tv_boxes']:.3f} ({n1}x{n2} boxes) / {a['tv_coarse']:.3f} "
                 f"({a['tv-bins']}x{a['tv-bins']} bins)")
    fig.tight_layout(rect=(0, BASIN_LEGEND_ROOM / 2 if nb else 0, 1, 1))
    save_atomic(fig, png)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
