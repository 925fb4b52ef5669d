#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws, over r, the fraction of expanding steps, the CLV angle quantiles and the angle histogram along orbits,
beside the median largest Lyapunov exponent, from a `btob hyperbolicity-orbits` file.

Usage: hyperbolicity_orbits.py DATA.h5 OUT.png
Reads only the HDF5 file; writes OUT.png atomically.
"""

import matplotlib

import plotlib  # noqa: E402  (Agg for the command line; a Python session keeps its backend)
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    return v.decode() if isinstance(v, bytes) else v


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    d = {k: f[k][...] for k in f.keys()}
    a = {k: attr(f, k) for k in f.attrs.keys()}
    r = d["r"]
    fig, axs = plt.subplots(4, 1, figsize=(10, 11), sharex=True,
                            gridspec_kw={"height_ratios": [1, 1, 1.2, 1]})
    ax = axs[0]
    ax.plot(r, d["lambda1_median"], "k.-", ms=3, lw=0.7, label=r"median $\lambda_1$ (fused cocycle kernel)")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_ylabel(r"$\lambda_1$ (per iteration)")
    ax.legend(fontsize=8, loc="upper right")
    ax = axs[1]
    ax.plot(r, d["frac_expanding"], "C3.-", ms=3, lw=0.7, label=r"fraction of steps with $s_1 \geq 1$")
    ax.plot(r, d["frac_degenerate"], "C0.-", ms=3, lw=0.7,
            label=r"fraction of orbits with $\lambda_1-\lambda_2 < 10/n$ (CLV angle undefined)")
    ax.set_ylim(-0.03, 1.03)
    ax.set_ylabel("fraction")
    ax.legend(fontsize=8, loc="lower right")
    ax = axs[2]
    deg = np.degrees
    ax.semilogy(r, deg(d["angle_median"]), "C2.-", ms=3, lw=0.7, label="median CLV angle")
    ax.semilogy(r, deg(d["angle_q05"]), "C1.-", ms=3, lw=0.7, label="5% quantile")
    ax.semilogy(r, deg(d["angle_min"]), "C4.", ms=2, label="minimum")
    ax.set_ylabel("angle between CLVs (degrees)")
    # A few labelled ticks only (labelling every minor tick piled them up).
    ax.yaxis.set_major_locator(matplotlib.ticker.FixedLocator([1, 2, 5, 10, 20, 45, 90]))
    ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.legend(fontsize=8, loc="lower right")
    # Where every orbit has lambda1 = lambda2 (within 10/n) the CLV angle is undefined: say so instead of
    # leaving the panels blank.
    undefined = d["frac_degenerate"] >= 0.999
    if undefined.any():
        dr_ = (r[-1] - r[0]) / max(1, len(r) - 1)
        starts = np.nonzero(undefined & ~np.r_[False, undefined[:-1]])[0]
        ends = np.nonzero(undefined & ~np.r_[undefined[1:], False])[0]
        for k, (i0, i1) in enumerate(zip(starts, ends)):
            for axx in (axs[2], axs[3]):
                axx.axvspan(r[i0] - dr_ / 2, r[i1] + dr_ / 2, color="#eeeeee", hatch="//", ec="#cccccc", lw=0, zorder=0)
            if r[i1] - r[i0] > 0.1 * (r[-1] - r[0]):
                for axx in (axs[2], axs[3]):
                    axx.text(0.5 * (r[i0] + r[i1]), 0.5, "CLV angle undefined here: every orbit has "
                             r"$\lambda_1 = \lambda_2$ within 10/n" + "\n(a rotation: complex-conjugate multipliers, on the invariant curves and on the sinks of this range)",
                             transform=axx.get_xaxis_transform(), ha="center", va="center", fontsize=8,
                             bbox=dict(facecolor="white", alpha=0.9, lw=0))
    ax = axs[3]
    h = d["angle_histogram"].astype(float)
    tot = h.sum(axis=1, keepdims=True)
    dens = np.divide(h, tot, out=np.full_like(h, np.nan), where=tot > 0)
    nb = h.shape[1]
    dr = (r[-1] - r[0]) / max(1, len(r) - 1) if len(r) > 1 else 0.01
    im = ax.imshow(dens.T, origin="lower", aspect="auto", extent=[r[0] - dr / 2, r[-1] + dr / 2, 0, 90],
                   cmap="magma", norm=mcolors.LogNorm(vmin=max(1e-5, np.nanmin(dens[dens > 0])) if np.any(dens > 0) else 1e-5,
                                                      vmax=1))
    ax.set_ylabel(f"CLV angle (degrees, {nb} bins)")
    ax.set_xlabel("restitution coefficient r")
    fig.colorbar(im, ax=axs, location="right", shrink=0.25, anchor=(0, 0.0), label="fraction of steps per bin")
    title = (a.get("title") or "").strip() or "Non-hyperbolicity along orbits: expanding steps and covariant Lyapunov vectors"
    axs[0].set_title(f"{title}\nr in [{float(a['r_min']):.4g}, {float(a['r_max']):.4g}] ({int(a['r_count'])} values), "
                     f"grid {a['grid']}, {int(a['iterations'])} iterations after {int(a['transient'])} transient "
                     f"(+{int(a['backward_transient'])} backward)", fontsize=10)
    return fig


if __name__ == "__main__":
    plotlib.main(draw, usage=__doc__, dpi=120, bbox_inches="tight")
