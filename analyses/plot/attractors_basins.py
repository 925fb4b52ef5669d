# SPDX-License-Identifier: GPL-3.0-or-later
"""Basin map at one r (btob basins): one colour per attractor, legend with patterns and fractions; below, the boundary
geometry: each entropy box's entropy (the boundary boxes) and the uncertain fraction f(eps) with its power-law fit.
Usage: attractors_basins.py NAME.h5 OUT.png   (reads NAME.h5 alone: labels, fraction, ci_low, ci_high, box_entropy,
uncertainty_* and the attributes; NAME_fractions.csv and NAME_boundary.csv hold the same numbers as tables)."""
import textwrap

import numpy as np
from matplotlib import colors
from matplotlib import pyplot as plt
from matplotlib.patches import Patch

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs


def rows_of(f):
    """The legend's rows (the columns of NAME_fractions.csv it uses) from the result itself: attractor ids 1..n with
    fraction and 95% interval, then the undecided points (id 0)."""
    a = attrs(f)
    out = []
    for i, (fr, lo, hi) in enumerate(zip(f["fraction"][...], f["ci_low"][...], f["ci_high"][...]), start=1):
        pattern, _, kind = a[f"legend_{i}"].rpartition(" (")
        out.append({"attractor": i, "type": kind.rstrip(")"), "pattern": pattern, "fraction": fr, "ci_low": lo,
                    "ci_high": hi})
    u = "undecided" if "undecided_fraction" in a else "unresolved"  # older files: unresolved_*
    out.append({"attractor": 0, "type": "undecided", "pattern": "", "fraction": a[f"{u}_fraction"],
                "ci_low": a.get(f"{u}_ci_low", float("nan")), "ci_high": a.get(f"{u}_ci_high", float("nan"))})
    return out


def draw_boxes(ax, f, a):
    """Each entropy box's entropy over the main grid's region (boxes from the grid's corner; a remainder left out)."""
    e = f["box_entropy"][...]
    box = int(a["entropy_box"])
    x1 = a["axis1_lo"] + (a["axis1_hi"] - a["axis1_lo"]) * e.shape[1] * box / int(a["n1"])
    x2 = a["axis2_lo"] + (a["axis2_hi"] - a["axis2_lo"]) * e.shape[0] * box / int(a["n2"])
    im = ax.imshow(np.where(e > 0, e, np.nan), origin="lower", cmap="viridis", interpolation="nearest",
                   aspect="auto", extent=[a["axis1_lo"], x1, a["axis2_lo"], x2], vmin=0,
                   vmax=max(float(e.max()), np.log(2)))  # at least log 2 (two basins, half each): one basin has 0
    ax.set_facecolor("#eeeeee")
    ax.figure.colorbar(im, ax=ax, label="box entropy (nats)")
    strip, sphere = a["grid_kind"] == "strip", a["grid_kind"] == "sphere"
    ax.set_xlabel("$w_1$" if strip else r"$\theta$ (rad)")
    ax.set_ylabel("$w_2$" if strip else (r"$y = -\cos\varphi$" if sphere else r"$\varphi$ (rad)"))
    fractal = " > log 2" if a["log2_criterion"] else ""
    ax.set_title(f"boundary boxes ({box} x {box} cells; grey: one basin): {a['boundary_boxes']} of "
                 f"{a['entropy_boxes']}\n$S_b$ = {a['basin_entropy']:.4f} [{a['basin_entropy_low']:.4f}, "
                 f"{a['basin_entropy_high']:.4f}], $S_{{bb}}$ = {a['boundary_basin_entropy']:.4f}{fractal}", fontsize=8)


def draw_uncertainty(ax, f, a):
    """f(eps) with its Clopper-Pearson 95% intervals, and the least-squares line of log f on log eps."""
    eps, frac = f["uncertainty_eps"][...], f["uncertainty_fraction"][...]
    lo, hi = f["uncertainty_ci_low"][...], f["uncertainty_ci_high"][...]
    ok = frac > 0
    ax.errorbar(eps[ok], frac[ok], yerr=[frac[ok] - lo[ok], hi[ok] - frac[ok]], fmt="o", ms=4, capsize=2,
                label="uncertain fraction (95% interval)")
    if a["uncertainty_fitted"]:
        alpha = float(a["uncertainty_exponent"])
        used = ok & (frac <= 0.5)  # the points fitted: 0 < f <= 1/2 (boundary.hpp)
        x, y = np.log(eps[used]), np.log(frac[used])
        c = y.mean() - alpha * x.mean()  # the least-squares line passes through the means
        e = np.array([eps[used].min(), eps[used].max()])
        ax.plot(e, np.exp(c) * e ** alpha, "-", color="C3",
                label=(f"fit: alpha = {alpha:.3f} [{a['uncertainty_exponent_low']:.3f}, "
                       f"{a['uncertainty_exponent_high']:.3f}], D = {a['boundary_dimension']:.3f}"))
        title = f"uncertainty exponent fitted (f <= 1/2) over eps = {a['uncertainty_eps_min_cells']}..{a['uncertainty_eps_max_cells']} cells"
    else:
        title = textwrap.fill("uncertainty exponent not fitted: " + str(a["uncertainty_note"]), 55)
    ax.set_xscale("log")
    if ok.any():
        ax.set_yscale("log")
        ax.legend(fontsize=7, loc="lower right")
    else:  # one basin: f = 0 at every eps, nothing to draw on a log scale
        ax.text(0.5, 0.5, "f(eps) = 0 at every eps:\nno boundary at the grid's resolution", transform=ax.transAxes,
                ha="center", va="center", fontsize=9)
        ax.set_yticks([])
    ax.set_xlabel(r"$\varepsilon$ (grid cells)")
    ax.set_ylabel(r"uncertain fraction $f(\varepsilon)$")
    ax.set_title(title + "\n" + textwrap.fill("Wada (merging): " + str(a["wada_verdict"]), 55), fontsize=8)


def draw(f):
    """The figure of an h5py-like f (an h5py.File or a btob Python result)."""
    a = attrs(f)
    labels = f["labels"][...]
    rows = rows_of(f)
    n_att = int(a["attractors"])
    # Colours: undecided black, then a qualitative palette by id (ids are sorted keys: stable across runs).
    palette = plt.get_cmap("tab20").colors
    cols = [(0, 0, 0)] + [palette[i % len(palette)] for i in range(n_att)]
    cmap = colors.ListedColormap(cols)
    norm = colors.BoundaryNorm(np.arange(-0.5, n_att + 1.5), n_att + 1)
    geometry = "box_entropy" in f  # files written before the boundary geometry have no lower row
    if geometry:
        # Two subfigures: the legend beside the map does not squeeze the lower row.
        fig = plt.figure(figsize=(10, 10), constrained_layout=True)
        top, bottom = fig.subfigures(2, 1, height_ratios=[1.2, 1])
        ax = top.subplots()
        lower = bottom.subplots(1, 2)
        draw_boxes(lower[0], f, a)
        draw_uncertainty(lower[1], f, a)
    else:
        fig, ax = plt.subplots(figsize=(9, 5.2), constrained_layout=True)
    ax.imshow(labels, origin="lower", cmap=cmap, norm=norm, interpolation="nearest", aspect="auto",
              extent=[a["axis1_lo"], a["axis1_hi"], a["axis2_lo"], a["axis2_hi"]])
    strip = a["grid_kind"] == "strip"
    r = float(a["r"])
    if strip:
        al = (1 + r) / 2
        w1 = np.linspace(a["axis1_lo"], a["axis1_hi"], 200)
        for s in (-1, 1):  # the P2 parallelogram w2 = 2 alpha w1 -+ 1 (Section 6.2)
            ax.plot(w1, 2 * al * w1 + s, color="white", lw=0.6, ls="--")
        ax.set_ylim(a["axis2_lo"], a["axis2_hi"])
    sphere = a["grid_kind"] == "sphere"  # equal-area chart: theta against the height y = -cos(phi)
    ax.set_xlabel("$w_1$" if strip else r"$\theta$ (rad)")
    ax.set_ylabel("$w_2$" if strip else (r"$y = -\cos\varphi$ (equal area)" if sphere else r"$\varphi$ (rad)"))
    n = int(a["n1"]) * int(a["n2"])
    measure = a.get("measure", "")
    # The title spans the figure (image and legend), wrapped to its width: over the axes alone it was cut off.
    fig.suptitle(f"basins at r = {r:g}: {a['n1']} x {a['n2']} {a['grid_kind']} grid, transient {a['transient']}, "
                 f"window {a['window']}\n" + textwrap.fill(f"fractions of the measure: {measure}", 110), fontsize=9)
    handles = []
    for row in rows:
        i = int(row["attractor"])
        frac = float(row["fraction"])
        lab = (f"{row['pattern'] or row['type']} [{row['type']}] "
               f"{100 * frac:.2f}% ({100 * float(row['ci_low']):.2f}-{100 * float(row['ci_high']):.2f})")
        handles.append(Patch(color=cols[i], label=lab))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, title=f"{n} points, Clopper-Pearson 95% intervals (sampling)")
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
