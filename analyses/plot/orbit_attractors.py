#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws r against attractor from a `btob lyapunov-map --attractors` or `btob bifurcation --attractors` file: at each
r the share of the grid's orbits that reached each attractor (stacked), with the windows of (ab)^n(cb)^n overlaid
(a strip above the shares, from the lower bound of each window to its r_crit,2(n), when the file has the windows
overlay).

Usage: orbit_attractors.py DATA.h5 OUT.png
The attractors are classify's verdicts (attractor_name, attractor_type); the most frequent ones get a colour each, the
rest are drawn together as "other".  Reads only the HDF5 file; writes OUT.png atomically (temporary file, then rename).
"""

import plotlib  # Agg for the command line (a Python session keeps its backend); atomic PNG writes
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SHOWN = 10  # attractors with a colour of their own (by total count); the others are "other"
FIXED = {"chaotic": "#d62728", "undecided": "#d9d9d9", "P2 invariant curves": "#2ca02c", "invariant curves": "#98df8a",
         "1": "#252525", "3": "#636363"}
# Colours of the periodic attractors: tab20 without its greens, reds and greys (kept for the fixed names above).
PALETTE = [0, 2, 8, 10, 12, 16, 18, 1, 3, 9, 11, 13, 17, 19]
R_CRIT_2 = 3 - 2 * 2 ** 0.5  # r_crit,2(2), the top of the widest window (n = 2)


def windows(f):
    """(lower bound, r_crit,2(n)) of each window whose two ends are in the file's overlay lines, widest r first."""
    if "overlay_lines" not in f or "overlay_labels" not in f:
        return []
    lines, labels = f["overlay_lines"][...], plotlib.texts(f, "overlay_labels")
    ends = sorted((float(v), "lower bound" in l, "r_crit,2" in l) for (v, _c), l in zip(lines, labels))
    # The windows are disjoint intervals [lower(n), r_crit,2(n)]: a lower bound followed by an r_crit,2 closes one.
    return sorted(((a[0], b[0]) for a, b in zip(ends, ends[1:]) if a[1] and b[2]), reverse=True)


def label_of(name, kind, period):
    if kind == "periodic":
        return f"{name} (period {period})"
    if kind == "collapse":
        return f"collapse (symbol {name})"
    return name


def layers_of(f):
    """The stacked shares [r] of the most frequent attractors, "other" and "undecided", with colours and labels."""
    count = f["attractor_count"][...].astype(float)
    names, kinds = plotlib.texts(f, "attractor_name"), plotlib.texts(f, "attractor_type")
    period = f["attractor_period"][...]
    share = count / count.sum(axis=1, keepdims=True)
    order = [i for i in np.argsort(-count.sum(axis=0), kind="stable") if count[:, i].sum() > 0 and names[i] != "undecided"]
    shown, rest = order[:SHOWN], order[SHOWN:]
    cmap = plt.get_cmap("tab20")
    layers, colours, legend = [], [], []
    k = 0
    for i in shown:
        layers.append(share[:, i])
        if names[i] in FIXED:
            colours.append(FIXED[names[i]])
        else:
            colours.append(cmap(PALETTE[k % len(PALETTE)]))
            k += 1
        legend.append(label_of(names[i], kinds[i], int(period[i])))
    if rest:
        layers.append(share[:, rest].sum(axis=1))
        colours.append("#8c8c8c")
        legend.append(f"other ({len(rest)} attractors)")
    u = names.index("undecided") if "undecided" in names else -1
    if u >= 0 and count[:, u].sum() > 0:
        layers.append(share[:, u])
        colours.append(FIXED["undecided"])
        legend.append("undecided (classify could not decide)")
    return layers, colours, legend


def draw_windows(wx, ax, f, r):
    """The windows of (ab)^n(cb)^n as bars in the strip wx (n named when the widest, n = 2, is in the file) and their
    ends as dashed lines on ax where a window is wide enough to see (they accumulate at 7 - 4 sqrt 3)."""
    wins = windows(f)
    numbered = bool(wins) and abs(wins[0][1] - R_CRIT_2) < 1e-9
    span = r[-1] - r[0]
    for k, (lo, hi) in enumerate(wins):
        wx.axvspan(lo, hi, color="#1f4fd6", alpha=0.6, lw=0)
        if numbered and hi - lo > 0.05 * span:  # room for the label inside the bar
            wx.text((lo + hi) / 2, 0.5, f"n = {k + 2}", ha="center", va="center", fontsize=8, color="w")
        if hi - lo > 0.01 * span:
            for v in (lo, hi):
                ax.axvline(v, color="#1f4fd6", lw=0.8, ls="--", zorder=3)
    wx.set_yticks([])
    wx.set_ylabel("windows", rotation=0, ha="right", va="center", fontsize=8)
    order = "n = 2, 3, ... from the right, " if numbered else ""
    wx.set_title(f"windows of (ab)^n(cb)^n ({order}each from its lower bound to r_crit,2(n)); dashed on the shares where "
                 f"wider than 1% of the axis", fontsize=8, loc="left")
    return wins


def draw(f):
    """The figure (returned, not saved) from an h5py-like f."""
    r = f["r"][...]
    a = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    layers, colours, legend = layers_of(f)
    fig, (wx, ax) = plt.subplots(2, 1, figsize=(11.5, 6.4), sharex=True, gridspec_kw={"height_ratios": [1, 12]})
    draw_windows(wx, ax, f, r)
    if len(r) > 1:
        ax.stackplot(r, *layers, colors=colours, labels=legend, lw=0, zorder=1)
    else:  # one r: a stacked bar
        bottom = 0.0
        for y, c, l in zip(layers, colours, legend):
            ax.bar(r, y, bottom=bottom, width=0.01, color=c, label=l)
            bottom += y
    ax.set_xlim(r[0], r[-1])
    ax.set_ylim(0, 1)
    ax.set_xlabel("restitution coefficient r (dimensionless)")
    ax.set_ylabel("share of the orbits (fraction of the grid's points)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    title = a.get("title") or "Attractor reached by each orbit against r"
    run = (f"{int(a['iterations'])} iterations after {int(a['transient'])} transient" if "transient" in a
           else f"{int(a['iterations'])} iterations")
    fig.suptitle(
        f"{title}\nr in [{float(a['r_min']):.4g}, {float(a['r_max']):.4g}], {int(a['r_count'])} values x grid "
        f"{a['grid']} ({int(a['initial_conditions'])} points, seed {a.get('seed', '')}), {run}; attractor: btob classify "
        f"over {int(a['attractor_iterations'])} iterations after {int(a['attractor_transient'])}",
        fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw, usage=__doc__, require="attractor_count", dpi=130)
