#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws a bifurcation diagram (density of tail values against r) from a `btob bifurcation` HDF5 file.

Usage: bifurcation.py DATA.h5 OUT.png
Reads only the HDF5 file; writes OUT.png atomically (temporary file, then rename).
The axes are padded so that values and lines on the range's edges (phi = 0 or pi, theta = 0 or pi/2, a
vertical line at r_max) stay visible; tail points outside the range are counted in the figure; vertical
overlay lines closer than a few pixels are thinned (and the figure says how many are drawn).  With the
trigonometric algorithm (Figure 4.7) three panels: what the paper's MATLAB code draws (complex
continuation past acos's domain), the orbits that stayed in the domain, and the share of orbits that left it.
"""
import sys

import h5py

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
AXIS_PX = 1350   # approximate width of the data area in pixels (figure 11 in at 150 dpi)
MIN_GAP_PX = 5   # overlay lines closer than this would merge into a solid block


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    return v.decode() if isinstance(v, bytes) else v


def fractions(dens):
    """Each r column normalised to the fraction of its tail points, columns averaged in groups when there
    are more r values than pixels (so that an r with a sink does not vanish)."""
    col = dens.sum(axis=1, keepdims=True)
    frac = np.divide(dens, np.maximum(col, 1))
    group = int(np.ceil(frac.shape[0] / 1400))
    if group > 1:
        pad = (-frac.shape[0]) % group
        frac = np.concatenate([frac, np.zeros((pad, frac.shape[1]))]).reshape(-1, group, frac.shape[1]).mean(axis=1)
    return frac


def draw_density(ax, frac, r0, r1, lo, hi):
    img = np.where(frac > 0, frac, np.nan).T
    positive = frac[frac > 0]
    vmin = max(positive.min(), 1e-6) if positive.size else 1e-6
    cmap = plt.get_cmap("magma_r").copy()
    cmap.set_bad("white")
    return ax.imshow(img, origin="lower", aspect="auto", extent=[r0, r1, lo, hi], interpolation="nearest", cmap=cmap,
                     norm=mcolors.LogNorm(vmin=vmin, vmax=max(positive.max(), vmin * 10) if positive.size else 1))


def thin(values, r0, r1):
    """The values (sorted) kept so that neighbours are at least MIN_GAP_PX apart, scanning from the largest r
    (where windows are wide) down; returns (kept, smallest kept value)."""
    v = np.sort(np.asarray(values))[::-1]
    kept, last = [], None
    px = AXIS_PX / (r1 - r0)
    for x in v:
        if last is None or (last - x) * px >= MIN_GAP_PX:
            kept.append(x)
            last = x
    return kept


def pad_axes(ax, r0, r1, lo, hi):
    dx, dy = 0.008 * (r1 - r0), 0.02 * (hi - lo)
    ax.set_xlim(r0 - dx, r1 + dx)
    ax.set_ylim(lo - dy, hi + dy)
    for y in (lo, hi):  # the range's edges, so that padded space is not read as empty data
        ax.axhline(y, color="#bbbbbb", lw=0.5, ls=":")


def overlays(ax, vlines, over, r0, r1):
    """Draws the vertical lines; overlay lines (all colours together) closer than MIN_GAP_PX to a line already
    drawn are skipped, scanning from the largest r; returns a note saying what was skipped."""
    for v in vlines:
        ax.axvline(v, color=COLOURS[0], lw=0.8, alpha=0.9)
    px = AXIS_PX / (r1 - r0)
    kept, last = [], None
    for rv, c in sorted(((float(rv), int(c)) for rv, c in over), key=lambda t: -t[0]):
        if last is None or (last - rv) * px >= MIN_GAP_PX:
            kept.append((rv, c))
            last = rv
    for rv, c in kept:
        ax.axvline(rv, color=COLOURS.get(c, "k"), lw=0.6, alpha=0.75)
    if len(kept) < len(over):
        return [f"overlay lines: {len(kept)} of {len(over)} drawn (lines closer than {MIN_GAP_PX} px to a drawn one "
                f"skipped; all drawn above r = {min(k[0] for k in kept):.6g})"]
    return []


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    dens = f["density"][...].astype(np.float32)  # (r_count, bins)
    dm = f["density_matlab"][...].astype(np.float32) if "density_matlab" in f else None
    complex_orbits = f["complex_orbits"][...] if "complex_orbits" in f else None
    nan_m = f["nan_points_matlab"][...] if "nan_points_matlab" in f else None
    stalled_m = f["stalled_matlab"][...] if "stalled_matlab" in f else None
    r = f["r"][...]
    vlines = f["vlines"][...] if "vlines" in f else np.zeros(0)
    over = f["overlay_lines"][...] if "overlay_lines" in f else np.zeros((0, 2))
    broken = f["broken"][...] if "broken" in f else np.zeros(0)
    a = {k: attr(f, k) for k in f.attrs.keys()}
    lo, hi = float(a["range_lo"]), float(a["range_hi"])
    coord = a["coord"]
    r0, r1 = float(r[0]), float(r[-1])
    if r1 == r0:
        r1 = r0 + 1e-12
    n_ic = int(a["initial_conditions"])
    total = float(a["r_count"]) * n_ic * float(a["tail"])
    below, above = int(a.get("points_below_range", 0)), int(a.get("points_above_range", 0))
    title = a.get("title") or a.get("name", "")
    sub = (f"r in [{a['r_min']:.10g}, {a['r_max']:.10g}], {a['r_count']} values; grid {a['grid']} "
           f"({n_ic} orbits per r); {a['iterations']} iterations, last {a['tail']} shown; "
           f"{a['scalar_type']}" + (f", {a['algorithm']} algorithm" if a.get("algorithm", "linear") != "linear" else ""))
    outside = (f"{below} tail points ({100 * below / total:.2g}%) below the range"
               + (" (theta = 0 included: log = -inf)" if coord == "log10-theta" else "")
               + f" and {above} above, not drawn" if below + above else "every tail point inside the range")

    if dm is None:
        fig, ax = plt.subplots(figsize=(11, 6.2), dpi=150)
        im = draw_density(ax, fractions(dens), r0, r1, lo, hi)
        del dens
        notes = overlays(ax, vlines, over, r0, r1)
        pad_axes(ax, r0, r1, lo, hi)
        ax.set_xlabel("restitution coefficient $r$ (dimensionless)")
        ax.set_ylabel(AXIS.get(coord, coord))
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.set_title(f"{title}\n{sub}" if title.strip() else sub, fontsize=10)
        fig.text(0.01, 0.008, "\n".join([outside] + notes), fontsize=7, va="bottom", color="#333333")
        cb = fig.colorbar(im, ax=ax, pad=0.01)
        cb.set_label("fraction of the tail points of each r (per bin)")
    else:
        # Figure 4.7: the paper's algorithm as it runs (complex continuation), the lab's reading, the failure.
        fig = plt.figure(figsize=(11, 11), dpi=150)
        gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.35], width_ratios=[1, 0.02], hspace=0.35, wspace=0.02)
        axes = [fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[2, 0])]
        # (a) covers Re acos in [0, pi], the whole range MATLAB can draw; the physical range [lo, hi] is marked.
        mlo, mhi = 0.0, float(np.pi)
        im = draw_density(axes[0], fractions(dm), r0, r1, mlo, mhi)
        draw_density(axes[1], fractions(dens), r0, r1, lo, hi)
        n_complex = int(complex_orbits.sum())
        n_broken = int(broken.sum())
        axes[0].set_title(f"{title}\n{sub}\n(a) what the paper's MATLAB code draws: every orbit, continued in complex "
                          f"arithmetic once acos leaves [-1, 1] (real part of theta plotted)", fontsize=9)
        axes[1].set_title(f"(b) only the orbits that never left acos's domain ({n_broken} of {len(r) * n_ic} orbits "
                          f"stopped and not drawn)", fontsize=9)
        for ax, (a_lo, a_hi) in zip(axes[:2], ((mlo, mhi), (lo, hi))):
            overlays(ax, vlines, over, r0, r1)
            pad_axes(ax, r0, r1, a_lo, a_hi)
            ax.set_ylabel(AXIS.get(coord, coord))
            ax.ticklabel_format(axis="x", useOffset=False)
        if stalled_m is not None and stalled_m.any():
            # The paper's red dots: r values at which the program could not compute enough iterations (some orbit
            # stopped producing b-collisions before the end of its tail: phi reached pi/2 exactly, where the printed
            # code changes nothing).
            red = r[stalled_m > 0]
            axes[0].plot(red, np.full(red.shape, mlo + 0.02 * (mhi - mlo)), ".", color="#d62020", ms=2.5,
                         label=f"r where some orbit stopped before {a['iterations']} iterations ({red.size} of {len(r)})")
            axes[0].legend(fontsize=7, loc="upper right", markerscale=3)
        axes[0].axhline(hi, color="#1f4fd6", lw=0.8, ls="--")
        axes[0].text(r1, hi, f" {AXIS.get(coord, coord).split(' (')[0]} = {hi:.4g}: above, outside the physical range",
                     fontsize=7, color="#1f4fd6", ha="right", va="bottom")
        n_nan = int(nan_m.sum()) if nan_m is not None else 0
        stalled_note = (f"; {int(stalled_m.sum())} tail states never reached (no more b-collisions)"
                        if stalled_m is not None and stalled_m.sum() else "")
        # The warning goes under the panel, not over the data.
        # Two lines: one would run under the colour bar.
        axes[0].text(0.0, -0.11, "past acos's domain this is the algorithm's failure, not the dynamics (compare Figure 4.1);\n"
                     f"{n_nan} NaN values not drawn{stalled_note}",
                     transform=axes[0].transAxes, fontsize=8, color="#b00000", va="top")
        ax = axes[2]
        ax.plot(r, 100 * complex_orbits / n_ic, color="#1f4fd6", lw=0.8, label="left acos's domain (complex)")
        ax.plot(r, 100 * broken / n_ic, color="k", lw=0.6, ls=":", label="stopped in (b) (any failure status)")
        if stalled_m is not None:
            ax.plot(r, 100 * stalled_m / (n_ic * float(a["tail"])), color="#d62020", lw=0.8,
                    label="(a) tail states never reached: no more b-collisions (the paper's red dots)")
        ax.set_ylim(-3, 103)
        ax.set_xlim(axes[0].get_xlim())
        ax.set_ylabel("% of orbits")
        ax.set_xlabel("restitution coefficient $r$ (dimensionless)")
        ax.set_title(f"(c) the algorithm's failures per r: orbits whose acos argument left [-1, 1] ({n_complex} in all), "
                     f"orbits stopped in (b), tail states (a) never reached", fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
        cb = fig.colorbar(im, cax=fig.add_subplot(gs[0:2, 1]))
        cb.set_label("fraction of the tail points of each r (per bin)")
    fig.text(0.995, 0.005, f"btob {a.get('btob_version', '')} {a.get('git_commit', '')}", ha="right", va="bottom",
             fontsize=6, color="#888888")
    if dm is None:
        fig.tight_layout(rect=(0, 0.045, 1, 1))
    return fig


def main(src, dst):
    with h5py.File(src, "r") as f:
        fig = draw(f)
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: bifurcation.py DATA.h5 OUT.png")
    main(sys.argv[1], sys.argv[2])
