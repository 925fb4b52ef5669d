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

import plotlib  # noqa: E402  (main: the command line)
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
MAX_FULL_LINES = 60  # more overlay lines than this are drawn as ticks in a band above the range (TICK_BAND of it)
TICK_BAND = 0.07


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


def pad_axes(ax, r0, r1, lo, hi, top=0.02, bottom=0.02):
    """Limits padded by `top` and `bottom` (fractions of the range) and the range's edges marked."""
    dx = 0.008 * (r1 - r0)
    ax.set_xlim(r0 - dx, r1 + dx)
    ax.set_ylim(lo - bottom * (hi - lo), hi + top * (hi - lo))
    for y in (lo, hi):  # the range's edges, so that padded space is not read as empty data
        ax.axhline(y, color="#bbbbbb", lw=0.5, ls=":")


def many_lines(over, r0, r1):
    """Whether the overlay lines kept at MIN_GAP_PX are more than MAX_FULL_LINES (drawn as ticks, above the range)."""
    return len(kept_lines(over, r0, r1)) > MAX_FULL_LINES


def kept_lines(over, r0, r1):
    """The overlay lines (r, colour) kept so that neighbours are at least MIN_GAP_PX apart, from the largest r."""
    px = AXIS_PX / (r1 - r0)
    kept, last = [], None
    for rv, c in sorted(((float(rv), int(c)) for rv, c in over), key=lambda t: -t[0]):
        if last is None or (last - rv) * px >= MIN_GAP_PX:
            kept.append((rv, c))
            last = rv
    return kept


def overlays(ax, vlines, over, r0, r1, hi):
    """Draws the vertical lines (after pad_axes: ticks need the final y limits); overlay lines (all colours
    together) closer than MIN_GAP_PX to a line already drawn are skipped, scanning from the largest r; returns notes
    saying what was skipped and how they are drawn."""
    for v in vlines:
        ax.axvline(v, color=COLOURS[0], lw=0.8, alpha=0.9)
    kept = kept_lines(over, r0, r1)
    # Many lines at the pixel spacing (Figure 4.5: windows n = 47..125) would hide the density between them: they
    # become ticks along the top edge, where each still marks its r, and the data below stays visible.
    ticks = len(kept) > MAX_FULL_LINES
    y0, y1 = ax.get_ylim()
    tick_from = (hi - y0) / (y1 - y0)  # the band pad_axes(top=TICK_BAND) left above the range
    for rv, c in kept:
        ax.axvline(rv, ymin=tick_from if ticks else 0, color=COLOURS.get(c, "k"), lw=0.8 if ticks else 0.6,
                   alpha=0.9 if ticks else 0.75)
    notes = []
    if len(kept) < len(over):
        notes.append(f"overlay lines: {len(kept)} of {len(over)} drawn (lines closer than {MIN_GAP_PX} px to a drawn one "
                     f"skipped; all drawn above r = {min(k[0] for k in kept):.6g})")
    if ticks:
        notes.append(f"overlay lines drawn as ticks in the band above the range ({len(kept)} lines: full-height lines "
                     "would hide the data between them)")
    return notes


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    dens = f["density"][...].astype(np.float32)  # (r_count, bins)
    dm = f["density_matlab"][...].astype(np.float32) if "density_matlab" in f else None
    r = f["r"][...]
    vlines = f["vlines"][...] if "vlines" in f else np.zeros(0)
    over = f["overlay_lines"][...] if "overlay_lines" in f else np.zeros((0, 2))
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
        pad_axes(ax, r0, r1, lo, hi, top=TICK_BAND if many_lines(over, r0, r1) else 0.02)
        notes = overlays(ax, vlines, over, r0, r1, hi)
        ax.set_xlabel("restitution coefficient $r$ (dimensionless)")
        ax.set_ylabel(AXIS.get(coord, coord))
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.set_title(f"{title}\n{sub}" if title.strip() else sub, fontsize=10)
        fig.text(0.01, 0.008, "\n".join([outside] + notes), fontsize=7, va="bottom", color="#333333")
        cb = fig.colorbar(im, ax=ax, pad=0.01)
        cb.set_label("fraction of the tail points of each r (per bin)")
    else:
        fig = draw_trig(f, a, dm, dens, r, vlines, over, title, sub)
    fig.text(0.995, 0.005, f"btob {a.get('btob_version', '')} {a.get('git_commit', '')}", ha="right", va="bottom",
             fontsize=6, color="#888888")
    if dm is None:
        fig.tight_layout(rect=(0, 0.045, 1, 1))
    return fig


def frozen_marks(ax, r, top_bin, y, label):
    """Marks the r values whose tail has points in the bin at theta = pi/2 (orbits frozen there: a one-pixel row of
    the image) with squares on that line, so that they are seen and not taken for the range's edge."""
    rf = r[top_bin > 0]
    if rf.size:
        ax.plot(rf, np.full(rf.shape, y), "s", ms=1.6, color="#0a7f5a", zorder=3,
                label=f"{label} ({rf.size} of {len(r)} r values)")


def red_dots(ax, r, stalled_m, iterations, y):
    """The paper's red dots: r values at which some orbit stopped producing b-collisions before the end of its tail
    (phi reached pi/2 exactly, where the printed code changes nothing), in the band below the data."""
    red = r[stalled_m > 0]
    ax.plot(red, np.full(red.shape, y), ".", color="#d62020", ms=2.5,
            label=f"r where some orbit stopped before {iterations} iterations ({red.size} of {len(r)}; drawn below "
                  f"theta = 0, off the data)")


def draw_trig(f, a, dm, dens, r, vlines, over, title, sub):
    """Figure 4.7: (a) the paper's algorithm as it runs (complex continuation, shown up to pi/2 like the paper's
    panel), (b) the orbits that stayed in acos's domain, (c) the failures per r."""
    complex_orbits = f["complex_orbits"][...]
    nan_m = f["nan_points_matlab"][...] if "nan_points_matlab" in f else None
    stalled_m = f["stalled_matlab"][...] if "stalled_matlab" in f else None
    broken = f["broken"][...] if "broken" in f else np.zeros(0)
    lo, hi = float(a["range_lo"]), float(a["range_hi"])
    r0, r1, n_ic = float(r[0]), float(r[-1]), int(a["initial_conditions"])
    fig = plt.figure(figsize=(11, 11), dpi=150)
    gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.35], width_ratios=[1, 0.02], hspace=0.38, wspace=0.02)
    axes = [fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[2, 0])]
    # density_matlab bins Re acos over [0, pi]; (a) shows [0, pi/2] and the bin holding pi/2 itself (an orbit frozen
    # at theta = pi/2 lands there), and counts what lies above (complex continuation past the physical range).
    width = np.pi / dm.shape[1]
    k_half = int(np.floor(hi / width))
    shown, above_pts = dm[:, :k_half + 1], int(dm[:, k_half + 1:].sum())
    im = draw_density(axes[0], fractions(shown), r0, r1, lo, (k_half + 1) * width)
    draw_density(axes[1], fractions(dens), r0, r1, lo, hi)
    axes[0].set_title(f"{title}\n{sub}\n(a) what the paper's MATLAB code draws: every orbit, continued in complex "
                      f"arithmetic once acos leaves [-1, 1] (real part of theta plotted)", fontsize=9)
    axes[1].set_title(f"(b) only the orbits that never left acos's domain ({int(broken.sum())} of {len(r) * n_ic} "
                      f"orbits stopped and not drawn)", fontsize=9)
    for ax in axes[:2]:
        overlays(ax, vlines, over, r0, r1, hi)
        ax.set_xlim(r0 - 0.008 * (r1 - r0), r1 + 0.008 * (r1 - r0))
        ax.set_ylim(lo - 0.1 * (hi - lo), hi + 0.03 * (hi - lo))
        ax.axhline(lo, color="#bbbbbb", lw=0.5, ls=":", zorder=0.5)
        ax.set_ylabel(AXIS.get(a["coord"], a["coord"]))
        ax.ticklabel_format(axis="x", useOffset=False)
    frozen_marks(axes[0], r, dm[:, k_half], hi, "r where some tail point sits at theta = pi/2 (frozen orbits)")
    frozen_marks(axes[1], r, dens[:, -1], hi, "r where some tail point is in the top bin (theta = pi/2)")
    if stalled_m is not None and stalled_m.any():
        red_dots(axes[0], r, stalled_m, a["iterations"], lo - 0.06 * (hi - lo))
    for ax in axes[:2]:
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="center right", markerscale=3, framealpha=0.9)  # empty there: r > 0.13, theta < 1.4
    n_nan = int(nan_m.sum()) if nan_m is not None else 0
    stalled_note = (f"; {int(stalled_m.sum())} tail states never reached (no more b-collisions)"
                    if stalled_m is not None and stalled_m.sum() else "")
    # The warning goes under the panel, not over the data; two lines: one would run under the colour bar.
    axes[0].text(0.0, -0.11, "past acos's domain this is the algorithm's failure, not the dynamics (compare Figure "
                 f"4.1);\n{n_nan} NaN values and {above_pts} tail points above pi/2 (complex continuation) not "
                 f"drawn{stalled_note}", transform=axes[0].transAxes, fontsize=8, color="#b00000", va="top")
    failures_panel(axes[2], a, r, complex_orbits, broken, stalled_m, n_ic, axes[0].get_xlim())
    cb = fig.colorbar(im, cax=fig.add_subplot(gs[0:2, 1]))
    cb.set_label("fraction of the tail points of each r (per bin)")
    return fig


def failures_panel(ax, a, r, complex_orbits, broken, stalled_m, n_ic, xlim):
    """(c) of Figure 4.7: per r, the orbits that left acos's domain, stopped in (b), tail states never reached."""
    ax.plot(r, 100 * complex_orbits / n_ic, color="#1f4fd6", lw=0.8, label="left acos's domain (complex)")
    ax.plot(r, 100 * broken / n_ic, color="k", lw=0.6, ls=":", label="stopped in (b) (any failure status)")
    if stalled_m is not None:
        ax.plot(r, 100 * stalled_m / (n_ic * float(a["tail"])), color="#d62020", lw=0.8,
                label="(a) tail states never reached: no more b-collisions (the paper's red dots)")
    ax.set_ylim(-3, 103)
    ax.set_xlim(xlim)
    ax.set_ylabel("% of orbits")
    ax.set_xlabel("restitution coefficient $r$ (dimensionless)")
    ax.set_title(f"(c) the algorithm's failures per r: orbits whose acos argument left [-1, 1] "
                 f"({int(complex_orbits.sum())} in all), orbits stopped in (b), tail states (a) never reached", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")


if __name__ == "__main__":
    plotlib.main(draw)
