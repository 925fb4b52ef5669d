#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compares the Figure 4.1 density images computed in float and in double.

Per r: the Kolmogorov-Smirnov distance between the two binned theta distributions (700 bins), and the
number of occupied bins (1 to a few on sinks, hundreds on chaotic r).  Writes distance.csv and
float_vs_double.png to OUTDIR.  Usage: float_vs_double.py FLOAT.h5 DOUBLE.h5 OUTDIR
A comparison of two runs (analyses/float_vs_double.sh), not one command's figure: it reads both HDF5 files.
"""
import json
import os
import sys

import h5py
import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    with h5py.File(path, "r") as f:
        return f["density"][...].astype(np.float64), f["r"][...], dict(f.attrs)


def main(fpath, dpath, out):
    df, r, af = load(fpath)
    dd, r2, ad = load(dpath)
    assert np.array_equal(r, r2)
    cf = np.cumsum(df, axis=1) / np.maximum(df.sum(axis=1, keepdims=True), 1)
    cd = np.cumsum(dd, axis=1) / np.maximum(dd.sum(axis=1, keepdims=True), 1)
    ks = np.abs(cf - cd).max(axis=1)
    occ_f, occ_d = (df > 0).sum(axis=1), (dd > 0).sum(axis=1)
    # distance.csv has one header line (numpy.genfromtxt(names=True) and the csv module read it as it is); what it
    # measures goes to distance.json beside it.
    def text(v):
        return v.decode() if isinstance(v, bytes) else v
    lo_, hi_ = float(ad.get("range_lo", 0)), float(ad.get("range_hi", np.pi / 2))
    about = {
        "description": "binned KS distance between float and double tails of the Figure 4.1 workload, over the "
                       "points inside the range",
        "bins": int(ad.get("bins", df.shape[1])), "coord": text(ad.get("coord", "theta")), "range": [lo_, hi_],
        "iterations": int(ad.get("iterations")), "tail": int(ad.get("tail")), "grid": text(ad.get("grid")),
        "columns": {"r": "restitution coefficient", "ks_distance": "max |CDF_float - CDF_double| over the bins",
                    "occupied_bins_float": "bins holding a float tail point",
                    "occupied_bins_double": "bins holding a double tail point"},
    }
    for name, content in (("distance.json", json.dumps(about, indent=2) + "\n"),
                          ("distance.csv", "r,ks_distance,occupied_bins_float,occupied_bins_double\n" + "".join(
                              f"{r[i]:.8f},{ks[i]:.4f},{occ_f[i]},{occ_d[i]}\n" for i in range(len(r))))):
        tmp = os.path.join(out, f"{name}.tmp-{os.getpid()}")
        with open(tmp, "w") as f:
            f.write(content)
        os.replace(tmp, os.path.join(out, name))

    import matplotlib.colors as mcolors
    lo, hi = float(ad.get("range_lo", 0)), float(ad.get("range_hi", np.pi / 2))
    # y range from the data: down to the bin above which 99.9% of the double tail points lie (the rest, theta
    # collapsing to 0 near 7-4*sqrt(3), is counted in the titles), instead of a fixed range that is mostly empty.
    edges = np.linspace(lo, hi, dd.shape[1] + 1)
    cum = np.cumsum(dd.sum(axis=0)) / max(dd.sum(), 1)
    ylo = float(edges[np.searchsorted(cum, 1e-3)])
    ylo = np.floor(ylo / 5) * 5
    fig, (a0, a2, a1) = plt.subplots(3, 1, figsize=(11, 10), dpi=130, sharex=True,
                                     gridspec_kw={"height_ratios": [2, 2, 1]})
    for ax, dens, name in ((a0, df, "float"), (a2, dd, "double")):
        frac = dens / np.maximum(dens.sum(axis=1, keepdims=True), 1)
        group = int(np.ceil(len(r) / 1400))
        if group > 1:
            pad = (-frac.shape[0]) % group
            frac = np.concatenate([frac, np.zeros((pad, frac.shape[1]))]).reshape(-1, group, frac.shape[1]).mean(axis=1)
        cmap = plt.get_cmap("magma_r").copy()
        cmap.set_bad("white")
        im = ax.imshow(np.where(frac > 0, frac, np.nan).T, origin="lower", aspect="auto", extent=[r[0], r[-1], lo, hi],
                       cmap=cmap, norm=mcolors.LogNorm(vmin=1e-4, vmax=1), interpolation="nearest")
        ax.set_ylabel(r"$\log_{10}\theta$ ($\theta$ in rad)")
        total = len(r) * 32 * int(ad.get("tail", 100))
        shown = dens[:, edges[:-1] >= ylo].sum()
        ax.set_ylim(ylo - 0.02 * (hi - ylo), hi + 0.02 * (hi - ylo))
        under = f"; theta < 1e{ylo:.0f} (incl. 0, not drawn): {100 * (1 - shown / total):.2g}% of points"
        ax.set_title(f"{name}: Figure 4.1 workload in log scale ({len(r)} r values, 32 orbits, "
                     f"{ad.get('iterations')} iterations, last {ad.get('tail')}){under}", fontsize=9)
        fig.colorbar(im, ax=ax, pad=0.01).set_label("fraction per bin")
    a1.plot(r, ks, lw=0.5, color="#333333")
    fig.colorbar(im, ax=a1, pad=0.01).ax.set_visible(False)  # same width as the panels above
    a1.set_xlabel("restitution coefficient $r$ (dimensionless)")
    a1.set_ylabel("KS distance\nfloat vs double\n(binned in log10 theta)")
    a1.set_ylim(0, max(0.05, 1.15 * ks.max()))
    a1.set_title(f"max {ks.max():.3f}, median {np.median(ks):.3f}; r with distance > 0.2: {(ks > 0.2).sum()} of {len(r)}",
                 fontsize=9)
    fig.tight_layout()
    save_atomic(fig, os.path.join(out, "float_vs_double.png"))
    print(f"float vs double: KS max {ks.max():.3f} at r = {r[ks.argmax()]:.6f}, median {np.median(ks):.4f}, "
          f"{(ks > 0.2).sum()} r values above 0.2")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: float_vs_double.py FLOAT.h5 DOUBLE.h5 OUTDIR")
    main(*sys.argv[1:])
