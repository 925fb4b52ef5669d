# SPDX-License-Identifier: GPL-3.0-or-later
"""Tails of individual orbits in the strip (w1, w2), one panel per orbit, titled by the classifier's verdict
(Figures 6.9-6.11).  Usage: strip_orbits.py RESULT.h5 OUT.png (reads only the HDF5 file: the verdicts are its
verdict, pattern, period and rotation datasets)"""
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np

from plotlib import attrs, save_atomic


def main(h5path, dst):
    with h5py.File(h5path, "r") as f:
        a = attrs(f)
        w1, w2 = f["w1"][()], f["w2"][()]
        rows = [{"verdict": v, "pattern": p, "period": int(n), "rotation": float(t)}
                for v, p, n, t in zip(f["verdict"].asstr()[()], f["pattern"].asstr()[()], f["period"][()],
                                      f["rotation"][()])]
    r = float(a["r"])
    alpha = (1 + r) / 2
    lim = float(a.get("plot_w1", 2))  # the command line's --plot-w1 and --only (Python results: their defaults)
    only = int(a.get("only", 0))
    idx = [only - 1] if only > 0 else list(range(len(rows)))
    n = len(idx)
    ncol = 1 if n == 1 else min(5, n)
    nrow = (n + ncol - 1) // ncol
    size = (10, 5.5) if n == 1 else (3.3 * ncol, 3.0 * nrow + 0.9)
    fig, axes = plt.subplots(nrow, ncol, figsize=size, squeeze=False, constrained_layout=True)
    colours = {"periodic": "tab:blue", "quasi-periodic": "tab:green", "chaotic": "tab:red"}
    for k, o in enumerate(idx):
        ax = axes[k // ncol][k % ncol]
        row = rows[o]
        verdict = row["verdict"]
        x, y = w1[o], w2[o]
        inside = np.abs(x) <= lim
        ax.plot(x[inside], y[inside], ".", ms=2.5 if verdict == "periodic" else 0.4, color=colours.get(verdict, "k"),
                rasterized=True)
        s = np.linspace(-lim, lim, 3)
        for sign in (-1, 1):  # the P2 parallelogram: w2 = 2 alpha w1 -+ 1 (Section 6.2)
            ax.plot(s, 2 * alpha * s + sign, color="0.6", lw=0.7, ls="--")
        ax.axvline(0, color="0.6", lw=0.7, ls=":")
        ax.set_xlim(-lim * 1.03, lim * 1.03)
        ax.set_ylim(-1.06, 1.06)
        if verdict == "periodic":
            what = f"periodic: {row['pattern']} (period {row['period']})"
        elif verdict == "quasi-periodic":
            what = f"quasi-periodic (rotation {float(row['rotation']):.4f})"
        else:
            what = verdict
        ax.set_title(f"orbit {o + 1}: {what}", fontsize=9)
        out = int((~inside).sum())
        if out:
            ax.text(0.02, 0.94, f"{out} of {len(x)} points have |w1| > {lim:g}", transform=ax.transAxes, fontsize=7,
                    color="0.3")
        if k // ncol == nrow - 1:
            ax.set_xlabel("$w_1$ (strip, eq. (6.4))")
        if k % ncol == 0:
            ax.set_ylabel("$w_2$")
    for k in range(n, nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    title = a.get("title") or "Orbits in the strip"
    counts = {}
    for row in rows:
        key = f"{row['verdict']} {row['pattern']}".strip()
        counts[key] = counts.get(key, 0) + 1
    summary = ", ".join(f"{c} {k}" for k, c in sorted(counts.items(), key=lambda kv: -kv[1]))
    fig.suptitle(f"{title}\nr = {r:g}; last {a['tail']} of {a['iterations']} iterations; start points random in the strip "
                 f"(w1 uniform in [{a['w1_min']:g}, {a['w1_max']:g}], w2 uniform in (-1, 1), seed {a['seed']})\n"
                 f"verdicts of the {len(rows)} orbits (btob's classifier): {summary}; "
                 f"dashed: w2 = 2 alpha w1 -+ 1, dotted: w1 = 0", fontsize=9)
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
