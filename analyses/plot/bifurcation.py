#!/usr/bin/env python3
"""Draws a bifurcation diagram (density of tail values against r) from a `btob bifurcation` HDF5 file.

Usage: bifurcation.py DATA.h5 OUT.png
Reads only the HDF5 file; writes OUT.png atomically (temporary file, then rename).
"""
import os
import sys

import h5py
import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = {0: "#d62728", 1: "#1f4fd6", 2: "#7f7f7f"}  # red, blue, grey (paper: bounds blue, r_crit,2 red)
AXIS = {
    "theta": r"$\theta$ (rad)",
    "log10-theta": r"$\log_{10}\theta$  ($\theta$ in rad)",
    "phi": r"$\varphi$ (rad)",
    "w1": r"$w_1$ (strip, dimensionless)",
    "w2": r"$w_2$ (strip, dimensionless)",
}


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    return v.decode() if isinstance(v, bytes) else v


def main(src, dst):
    with h5py.File(src, "r") as f:
        dens = f["density"][...].astype(np.float32)  # (r_count, bins)
        r = f["r"][...]
        vlines = f["vlines"][...] if "vlines" in f else np.zeros(0)
        over = f["overlay_lines"][...] if "overlay_lines" in f else np.zeros((0, 2))
        broken = f["broken"][...] if "broken" in f else np.zeros(0)
        a = {k: attr(f, k) for k in f.attrs.keys()}
    lo, hi = float(a["range_lo"]), float(a["range_hi"])
    coord = a["coord"]

    fig, ax = plt.subplots(figsize=(11, 6.2), dpi=150)
    # Columns are r values; normalise each column to the fraction of its tail points (so the picture
    # does not depend on the grid size) and show it with a logarithmic colour scale.
    col = dens.sum(axis=1, keepdims=True)
    frac = np.divide(dens, np.maximum(col, 1))
    # More r columns than the axes have pixels: average groups of adjacent columns instead of letting
    # the renderer drop columns (an r with a sink would vanish), and keep memory small.
    group = int(np.ceil(frac.shape[0] / 1400))
    if group > 1:
        pad = (-frac.shape[0]) % group
        frac = np.concatenate([frac, np.zeros((pad, frac.shape[1]))]).reshape(-1, group, frac.shape[1]).mean(axis=1)
    del dens
    img = np.where(frac > 0, frac, np.nan).T
    r0, r1 = float(r[0]), float(r[-1])
    if r1 == r0:
        r1 = r0 + 1e-12
    positive = frac[frac > 0]
    vmin = max(positive.min(), 1e-6) if positive.size else 1e-6
    cmap = plt.get_cmap("magma_r").copy()
    cmap.set_bad("white")
    im = ax.imshow(img, origin="lower", aspect="auto", extent=[r0, r1, lo, hi], interpolation="nearest",
                   cmap=cmap, norm=mcolors.LogNorm(vmin=vmin, vmax=max(positive.max(), vmin * 10) if positive.size else 1))
    for v in vlines:
        ax.axvline(v, color=COLOURS[0], lw=0.8, alpha=0.9)
    for rv, c in over:
        ax.axvline(rv, color=COLOURS.get(int(c), "k"), lw=0.6, alpha=0.75)
    if broken.size and broken.sum() > 0:
        # Paper, Figure 4.7: red dots mark r values where the trigonometric algorithm could not iterate.
        bad = r[broken > 0]
        ax.plot(bad, np.full(bad.shape, hi - 0.01 * (hi - lo)), ".", color=COLOURS[0], ms=2,
                label=f"orbits broken down (acos singular) at {bad.size} r values")
        ax.legend(loc="lower right", fontsize=8)
    ax.set_xlim(r0, r1)
    ax.set_ylim(lo, hi)
    ax.set_xlabel("restitution coefficient $r$ (dimensionless)")
    ax.set_ylabel(AXIS.get(coord, coord))
    ax.ticklabel_format(axis="x", useOffset=False)
    title = a.get("title") or a.get("name", "")
    sub = (f"r in [{a['r_min']:.10g}, {a['r_max']:.10g}], {a['r_count']} values; grid {a['grid']} "
           f"({a['initial_conditions']} orbits per r); {a['iterations']} iterations, last {a['tail']} shown; "
           f"{a['scalar_type']}" + (f", {a['algorithm']} algorithm" if a.get("algorithm", "linear") != "linear" else ""))
    ax.set_title(f"{title}\n{sub}" if title.strip() else sub, fontsize=10)
    cb = fig.colorbar(im, ax=ax, pad=0.01)
    cb.set_label("fraction of the tail points of each r (per bin)")
    fig.text(0.995, 0.005, f"btob {a.get('btob_version', '')} {a.get('git_commit', '')}", ha="right", va="bottom",
             fontsize=6, color="#888888")
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: bifurcation.py DATA.h5 OUT.png")
    main(sys.argv[1], sys.argv[2])
