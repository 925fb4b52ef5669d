#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the largest Lyapunov exponent at one r over a strip grid (w1, w2) from a `btob lyapunov-strip` file.

Usage: lyapunov_strip.py DATA.h5 OUT.png
The partition boundaries of the strip (eq. (6.4)) are overlaid: w2 = 2 alpha w1 - 1 (alpha y = x: branch 1
below it), w2 = 2 alpha w1 + 1 (alpha y = z: branch 3 above it) and w1 = 0.
Reads only the HDF5 file; writes OUT.png atomically.
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
    lam = f["lambda1"][...]
    a = {k: attr(f, k) for k in f.attrs.keys()}
    w1lo, w1hi, alpha = float(a["w1_min"]), float(a["w1_max"]), float(a["alpha"])
    fig, ax = plt.subplots(figsize=(9, 5.5))
    vmax = max(1e-3, float(np.max(np.abs(lam))))
    im = ax.imshow(lam.T, origin="lower", extent=[w1lo, w1hi, -1, 1], aspect="auto", cmap="RdBu_r",
                   norm=mcolors.TwoSlopeNorm(vmin=min(-1e-3, float(lam.min())), vcenter=0.0, vmax=vmax))
    w = np.linspace(w1lo, w1hi, 400)
    ax.plot(w, 2 * alpha * w - 1, "k-", lw=0.8, label=r"$w_2 = 2\alpha w_1 - 1$ ($\alpha y = x$)")
    ax.plot(w, 2 * alpha * w + 1, "k--", lw=0.8, label=r"$w_2 = 2\alpha w_1 + 1$ ($\alpha y = z$)")
    ax.axvline(0, color="k", lw=0.6, ls=":", label=r"$w_1 = 0$")
    ax.set_ylim(-1, 1)
    ax.set_xlim(w1lo, w1hi)
    ax.set_xlabel(r"$w_1 = y/(x-z)$ (strip coordinate, dimensionless)")
    ax.set_ylabel(r"$w_2 = (x+z)/(x-z)$ (dimensionless)")
    ax.legend(loc="lower right", fontsize=8)
    fig.colorbar(im, ax=ax, label=r"$\lambda_1$ (per iteration, natural log)")
    title = a.get("title") or "Largest Lyapunov exponent over initial conditions"
    ax.set_title(f"{title}\nr = {float(a['r']):.6g}, grid {a['grid']}, {int(a['iterations'])} iterations after "
                 f"{int(a['transient'])} transient", fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw, usage=__doc__, dpi=130)
