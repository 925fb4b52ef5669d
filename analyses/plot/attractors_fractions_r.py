# SPDX-License-Identifier: GPL-3.0-or-later
"""Basin fractions across r (btob basins-r): stacked areas, attractors matched across r by pattern; below (with a
boundary grid), the basin entropies S_b, S_bb with their intervals and the uncertainty exponent against r."""

import numpy as np
from matplotlib import pyplot as plt

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    a = attrs(f)
    r = f["r"][...]
    frac = f["fraction"][...]
    names = [a[f"column_{i}"] for i in range(int(a["columns"]))]
    order = np.argsort(r)
    order_r = order
    r, frac = r[order], frac[order]
    x = np.arange(len(r))  # r values of Table 6.1 are uneven: equal spacing, labelled by r
    geometry = "basin_entropy" in f
    if geometry:
        fig, (ax, bx) = plt.subplots(2, 1, figsize=(11, 8.6), constrained_layout=True, height_ratios=[1.3, 1],
                                     sharex=True)
    else:
        fig, ax = plt.subplots(figsize=(11, 5), constrained_layout=True)
    # Colours: one distinct hue per pattern family (a pattern and its J-mirror, 132^n / 312^n, share it; the
    # mirror is hatched), so that different patterns never get near-identical shades; every segment taller than
    # 6% is labelled on the bar itself.  Quasi-periodic teal, chaotic dark red (hatched), collapse grey,
    # undecided black.
    fixed = {"quasi-periodic": "#17becf", "chaotic": "#8b0000", "collapse": "#7f7f7f", "undecided": "#000000"}

    def family(n):
        p = n.split(" (")[0]
        return ("132" + p[3:]) if p.startswith("312^") else p

    def mirrored(n):
        return n.split(" (")[0].startswith("312^")

    hues = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#393b79",
            "#637939", "#e7ba52", "#ad494a", "#7b4173", "#3182bd", "#31a354", "#756bb1"]
    fams = []
    for n in names:
        if not any(n.endswith(f"({t})") or n == t for t in fixed) and family(n) not in fams:
            fams.append(family(n))
    cols, hatches = [], []
    for n in names:
        kind = next((t for t in fixed if n.endswith(f"({t})") or n == t), None)
        cols.append(fixed[kind] if kind else hues[fams.index(family(n)) % len(hues)])
        hatches.append("//" if kind == "chaotic" else ("..." if mirrored(n) else None))
    rank = {"quasi-periodic": 1, "chaotic": 2, "collapse": 3, "undecided": 4}
    order = sorted(range(len(names)), key=lambda j: (next((v for t, v in rank.items() if t in names[j]), 0),
                                                     fams.index(family(names[j])) if family(names[j]) in fams else 0, j))
    names, cols, hatches, frac = ([names[j] for j in order], [cols[j] for j in order], [hatches[j] for j in order],
                                  frac[:, order])
    bottom = np.zeros(len(r))
    for j, (n, c, h) in enumerate(zip(names, cols, hatches)):
        ax.bar(x, frac[:, j], bottom=bottom, width=0.9, color=c, label=n, hatch=h,
               edgecolor="white" if h else None, linewidth=0)
        for i in range(len(r)):
            if frac[i, j] >= 0.06:
                short = n.split(" (")[0].replace("P2 invariant curves", "Q2")
                ax.text(x[i], bottom[i] + frac[i, j] / 2, short, rotation=90, ha="center", va="center", fontsize=6,
                        color="white" if c not in ("#17becf", "#bcbd22", "#e7ba52") else "black")
        bottom += frac[:, j]
    ax.set_xticks(x)
    ax.set_xticklabels([f"{v:g}" for v in r], rotation=60, fontsize=8)
    ax.set_xlim(x[0] - 0.6, x[-1] + 0.6)
    ax.set_ylim(0, 1)
    ax.set_xlabel("r (Table 6.1 values, equally spaced)")
    ax.set_ylabel("basin fraction of the measure" if a.get("measure") else "basin fraction")
    ax.set_title(f"Basin fractions across r (Table 6.1 values): {a['points']} initial conditions per r "
                 f"({a['grid']}, seed {a['seed']}), transient {a['transient']}, window {a.get('window', a.get('iterations', '?'))}"
                 + (f"\nmeasure: {a['measure']}" if a.get("measure") else ""),
                 fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7,
              title="dotted: J-mirror (312^n of 132^n)\nQ2 on the bars: P2 invariant curves", title_fontsize=7)
    if geometry:
        draw_geometry(bx, f, a, x, order_r)
    return fig


def draw_geometry(ax, f, a, x, order):
    """S_b, S_bb (t 95% intervals over the replicate grids), the boundary-box share and alpha (fit interval) per r."""
    def col(name):
        return f[name][...][order]
    for name, label, color in (("basin_entropy", "$S_b$", "C0"), ("boundary_basin_entropy", "$S_{bb}$", "C1")):
        v, lo, hi = col(name), col(name + "_low"), col(name + "_high")
        ax.errorbar(x - 0.1 if name == "basin_entropy" else x + 0.1, v, yerr=[v - lo, hi - v], fmt="o", ms=4,
                    capsize=2, color=color, label=label)
    ax.plot(x, col("boundary_box_share"), "s", ms=3, color="C2", label="boundary-box share")
    ax.axhline(np.log(2), color="grey", ls="--", lw=0.8, label="log 2 ($S_{bb}$ above: fractal boundary)")
    ax.set_ylabel("entropy (nats) / share")
    ax.set_xlabel("r (equally spaced)")
    ax.tick_params(axis="x", labelrotation=60, labelsize=8)  # the shared axis: its labels are this panel's
    tx = ax.twinx()
    fit = col("uncertainty_fitted") > 0
    al, lo, hi = col("uncertainty_exponent"), col("uncertainty_exponent_low"), col("uncertainty_exponent_high")
    tx.errorbar(x[fit] + 0.25, al[fit], yerr=[al[fit] - lo[fit], hi[fit] - al[fit]], fmt="D", ms=4, capsize=2,
                color="C3", label=r"uncertainty exponent $\alpha$ (95% fit interval)")
    tx.axhline(1, color="C3", ls=":", lw=0.8)
    tx.set_ylabel(r"$\alpha$ ($D = 2 - \alpha$; 1: smooth boundary)", color="C3")
    tx.set_ylim(0, max(1.2, float(np.max(hi[fit])) + 0.05) if fit.any() else 1.2)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = tx.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, loc="upper left", bbox_to_anchor=(1.06, 1), fontsize=7)
    ax.set_title(f"boundary geometry on {a['boundary_grid']} ({a['boundary_replicates']} replicate grids), entropy "
                 f"boxes of {a['entropy_box']} cells", fontsize=9)


if __name__ == "__main__":
    plotlib.main(draw)
