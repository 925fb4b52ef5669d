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
    x = np.arange(len(r))  # r values of Table 5.1 are uneven: equal spacing, labelled by r
    fig, ax = plt.subplots(figsize=(11, 5), constrained_layout=True)
    cmap = plt.get_cmap("tab20").colors
    cols = [cmap[i % len(cmap)] for i in range(len(names) - 1)] + [(0, 0, 0)]
    ax.stackplot(x, frac.T, labels=names, colors=cols, step="mid")  # one bar per r: no interpolation across gaps
    ax.set_xticks(x)
    ax.set_xticklabels([f"{v:g}" for v in r], rotation=60, fontsize=8)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(0, 1)
    ax.set_xlabel("r (Table 5.1 values, equally spaced)")
    ax.set_ylabel("basin fraction")
    ax.set_title(f"basin fractions, {a['points']} initial conditions ({a['grid']}, seed {a['seed']}) per r", fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7)
    save_atomic(fig, png_path)


if __name__ == "__main__":
    main(*sys.argv[1:3])
