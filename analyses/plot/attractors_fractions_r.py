"""Basin fractions across r (btob basins-r): stacked areas, attractors matched across r by pattern."""
import sys

import h5py
import numpy as np
from matplotlib import pyplot as plt

from plotlib import attrs, save_atomic


def main(h5_path, png_path):
    with h5py.File(h5_path, "r") as f:
        a = attrs(f)
        r = f["r"][...]
        frac = f["fraction"][...]
    names = [a[f"column_{i}"] for i in range(int(a["columns"]))]
    order = np.argsort(r)
    r, frac = r[order], frac[order]
    x = np.arange(len(r))  # r values of Table 6.1 are uneven: equal spacing, labelled by r
    fig, ax = plt.subplots(figsize=(11, 5), constrained_layout=True)
    # Colours by type: periodic patterns from tab20, quasi-periodic teal, chaotic dark red, collapse grey,
    # unresolved black; one stacked bar per r (the r values are uneven, so no areas across gaps).
    fixed = {"quasi-periodic": "#17becf", "chaotic": "#8b0000", "collapse": "#7f7f7f", "unresolved": "#000000"}
    pal = [c for i, c in enumerate(plt.get_cmap("tab20").colors) if i not in (14, 15, 18, 19)]
    pal += list(plt.get_cmap("tab20b").colors)  # 36 distinct colours before any repeats
    cols, k = [], 0
    for n in names:
        kind = next((t for t in fixed if n.endswith(f"({t})") or n == t), None)
        if kind:
            cols.append(fixed[kind])
        else:
            cols.append(pal[k % len(pal)])
            k += 1
    rank = {"quasi-periodic": 1, "chaotic": 2, "collapse": 3, "unresolved": 4}
    order = sorted(range(len(names)), key=lambda j: (next((v for t, v in rank.items() if t in names[j]), 0), j))
    names, cols, frac = [names[j] for j in order], [cols[j] for j in order], frac[:, order]
    bottom = np.zeros(len(r))
    for j, (n, c) in enumerate(zip(names, cols)):
        ax.bar(x, frac[:, j], bottom=bottom, width=0.9, color=c, label=n, hatch="//" if "chaotic" in n else None,
               edgecolor="white" if "chaotic" in n else None, linewidth=0)
        bottom += frac[:, j]
    ax.set_xticks(x)
    ax.set_xticklabels([f"{v:g}" for v in r], rotation=60, fontsize=8)
    ax.set_xlim(x[0] - 0.6, x[-1] + 0.6)
    ax.set_ylim(0, 1)
    ax.set_xlabel("r (Table 6.1 values, equally spaced)")
    ax.set_ylabel("basin fraction")
    ax.set_title(f"Basin fractions across r (Table 6.1 values): {a['points']} initial conditions per r "
                 f"({a['grid']}, seed {a['seed']}), transient {a['transient']}, window {a.get('window', a.get('iterations', '?'))}",
                 fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7)
    save_atomic(fig, png_path)


if __name__ == "__main__":
    main(*sys.argv[1:3])
