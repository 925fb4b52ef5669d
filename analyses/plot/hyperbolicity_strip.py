#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws log10 of the largest singular value s1 of the one-step derivative at one r over a strip grid (w1, w2),
from a `btob hyperbolicity` file.

Usage: hyperbolicity_strip.py DATA.h5 OUT.png
Overlays the partition boundaries of the strip (eq. (6.4): w2 = 2 alpha w1 -+ 1, w1 = 0) and the contour s1 = 1
(expanding where s1 >= 1).  Reads only the HDF5 file; writes OUT.png atomically.
"""

import plotlib  # noqa: E402  (Agg for the command line; a Python session keeps its backend)
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    return v.decode() if isinstance(v, bytes) else v


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    s1 = f["s1"][...]
    w1 = f["w1"][...]
    w2 = f["w2"][...]
    a = {k: attr(f, k) for k in f.attrs.keys()}
    w1lo, w1hi, alpha = float(a["w1_min"]), float(a["w1_max"]), float(a["alpha"])
    ls = np.log10(s1)
    fig, ax = plt.subplots(figsize=(9, 5.5))
    im = ax.imshow(ls.T, origin="lower", extent=[w1lo, w1hi, -1, 1], aspect="auto", cmap="RdBu_r",
                   norm=mcolors.TwoSlopeNorm(vmin=min(-0.05, float(ls.min())), vcenter=0.0,
                                             vmax=max(0.05, float(ls.max()))))
    if ls.min() < 0 < ls.max():
        ax.contour(w1[:, 0], w2[0, :], ls.T, levels=[0.0], colors="gold", linewidths=1.2)
    w = np.linspace(w1lo, w1hi, 400)
    ax.plot(w, 2 * alpha * w - 1, "k-", lw=0.8, label=r"$w_2 = 2\alpha w_1 - 1$ ($\alpha y = x$)")
    ax.plot(w, 2 * alpha * w + 1, "k--", lw=0.8, label=r"$w_2 = 2\alpha w_1 + 1$ ($\alpha y = z$)")
    ax.axvline(0, color="k", lw=0.6, ls=":", label=r"$w_1 = 0$")
    ax.plot([], [], color="gold", lw=1.2, label=r"$s_1 = 1$ (expanding where $s_1 \geq 1$)")
    ax.set_ylim(-1, 1)
    ax.set_xlim(w1lo, w1hi)
    ax.set_xlabel(r"$w_1 = y/(x-z)$ (strip coordinate, dimensionless)")
    ax.set_ylabel(r"$w_2 = (x+z)/(x-z)$ (dimensionless)")
    ax.legend(loc="lower right", fontsize=8, framealpha=0.85)
    fig.colorbar(im, ax=ax, label=r"$\log_{10} s_1$, largest singular value of $D\widehat{P}_r$ (sphere metric)")
    title = (a.get("title") or "").strip() or "Largest singular value of the one-step derivative"
    ax.set_title(f"{title}\nr = {float(a['r']):.6g}, grid {a['grid']}, expanding fraction "
                 f"{float(a['expanding_fraction']):.3f}", fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw, usage=__doc__, dpi=130)
