"""Basin fractions across r (btob basins-r): stacked areas, attractors matched across r by pattern."""
import sys

import h5py
import numpy as np
from matplotlib import pyplot as plt

from plotlib import attrs, save_atomic


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    a = attrs(f)
    r = f["r"][...]
    frac = f["fraction"][...]
    names = [a[f"column_{i}"] for i in range(int(a["columns"]))]
    order = np.argsort(r)
    r, frac = r[order], frac[order]
    x = np.arange(len(r))  # r values of Table 6.1 are uneven: equal spacing, labelled by r
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
    return fig


def main(h5_path, png_path):
    with h5py.File(h5_path, "r") as f:
        fig = draw(f)
    save_atomic(fig, png_path)


if __name__ == "__main__":
    main(*sys.argv[1:3])
