#!/usr/bin/env python3
"""Draws C_N(phi, psi; n) (linear and log |C_N|) and the power spectrum from a `btob correlate` HDF5 file.
Usage: stats_correlation.py DATA.h5 OUT.png"""
import os
import sys

import h5py
import matplotlib

from plotlib import attrs, save_atomic  # noqa: F401  (also selects the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(src, dst):
    with h5py.File(src, "r") as f:
        c = f["C_N"][...]
        ps = f["power_spectrum"][...]
        a = attrs(f)
    n = np.arange(len(c))
    fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(15, 4.6), dpi=130)
    ax.plot(n, c, lw=0.8)
    ax.set_xlabel("lag n (map iterations)")
    ax.set_ylabel(r"$C_N(n)$")
    bx.semilogy(n, np.abs(c) + 1e-300, lw=0.8)
    if "decay_rate" in a:
        bx.set_title(f"fitted decay rate {a['decay_rate']:.3g} +- {a['decay_rate_error']:.2g} per iteration", fontsize=9)
    bx.set_xlabel("lag n (map iterations)")
    bx.set_ylabel(r"$|C_N(n)|$")
    freq = np.arange(len(ps)) / (2 * (len(ps) - 1))
    cx.semilogy(freq[1:], ps[1:] + 1e-300, lw=0.5)
    cx.set_xlabel("frequency (cycles per iteration)")
    cx.set_ylabel("power spectrum of the first observable")
    fig.suptitle(f"C_N({a['observables']}; n) at r = {a['r']}, from {a['point']}, N = {a['N']}, transient {a['transient']}, "
                 f"{a['method']}, double", fontsize=10)
    fig.tight_layout()
    save_atomic(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: stats_correlation.py DATA.h5 OUT.png")
    main(*sys.argv[1:])
