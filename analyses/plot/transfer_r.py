# SPDX-License-Identifier: GPL-3.0-or-later
"""Peripheral spectrum of Ulam's operator across r with the gap, the thresholds and the windows (btob transfer-r).
Usage: transfer_r.py NAME.h5 OUT.png   (reads NAME.h5 alone: r, re, im, gap, peripheral_count, window_lower,
window_upper and the attributes boxes, samples, peripheral).  NaN values (no gap, no upper end of the window n = 1)
are undefined values; eigenvalues that did not converge (NaN) are left out."""

import numpy as np

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs

import matplotlib.pyplot as plt


def draw(f):
    """The figure of an h5py-like f (the datasets and attributes `btob transfer-r` writes)."""
    a = attrs(f)
    boxes, samples, tol = a["boxes"], a["samples"], float(a["peripheral"])
    r = np.asarray(f["r"][...])
    re, im = np.asarray(f["re"][...]), np.asarray(f["im"][...])  # r x K, NaN where fewer converged
    ok = np.isfinite(re)
    s = {"r": np.repeat(r, re.shape[1]).reshape(re.shape)[ok], "re": re[ok], "im": im[ok]}
    s["modulus"] = np.hypot(s["re"], s["im"])
    p = {"r": r, "gap": np.asarray(f["gap"][...]), "peripheral_count": np.asarray(f["peripheral_count"][...])}
    lower = np.asarray(f["window_lower"][...])
    w = {"n": np.arange(1, len(lower) + 1), "lower": lower, "upper": np.asarray(f["window_upper"][...])}
    rmin, rmax = p["r"].min(), p["r"].max()
    fig, ax = plt.subplots(3, 1, figsize=(12, 11), sharex=True)
    periph = 1 - s["modulus"] < tol
    ax[0].scatter(s["r"][~periph], s["modulus"][~periph], s=4, color="0.5", label="|lambda_k|, rest")
    ax[0].scatter(s["r"][periph], s["modulus"][periph], s=6, color="tab:red", label=f"peripheral: 1 - |lambda| < {tol}")
    ax[0].set_ylabel("|lambda_k|")
    ax[0].set_ylim(max(0, s["modulus"].min() - 0.02), 1.005)
    ax[0].legend(loc="lower right", fontsize=8)
    arg = np.abs(np.arctan2(s["im"], s["re"]))
    ax[1].scatter(s["r"][periph], arg[periph] / (2 * np.pi), s=6, color="tab:red", label="peripheral eigenvalues")
    rr = np.linspace(max(rmin, 3 - 2 * np.sqrt(2)), rmax, 400)
    beta = np.arccos(np.clip(-(1 - rr) ** 2 / (4 * rr), -1, 1))
    for k in range(1, 5):
        frac = np.abs(np.angle(np.exp(1j * k * beta))) / (2 * np.pi)
        ax[1].plot(rr, frac, lw=0.8, color="tab:green", alpha=0.7, label="|k beta| mod 2pi, k = 1..4" if k == 1 else None)
    ax[1].set_ylabel("|arg lambda| / 2 pi (turns)")
    ax[1].legend(loc="upper right", fontsize=8)
    # The gap that matters for Section 8: 1 - |lambda| of the largest eigenvalue off the unit circle (the exact
    # roots of unity of the closed classes, |lambda| > 1 - 1e-9, excluded).
    off = s["modulus"] < 1 - 1e-9
    rs = np.unique(s["r"])
    gap2 = np.array([1 - s["modulus"][(s["r"] == r) & off].max() if np.any((s["r"] == r) & off) else np.nan for r in rs])
    ax[2].plot(rs, gap2, ".-", ms=3, lw=0.8, color="tab:blue", label="1 - |lambda| of the leading eigenvalue off the unit circle")
    ax[2].plot(p["r"], p["gap"], ".-", ms=2, lw=0.6, color="tab:orange", alpha=0.7,
               label=f"min |peripheral| - max |rest| (peripheral: 1 - |lambda| < {tol})")
    ax[2].set_yscale("log")
    ax[2].set_ylabel("gap")
    ax2 = ax[2].twinx()
    ax2.step(p["r"], p["peripheral_count"], where="mid", color="tab:red", lw=0.8, label="peripheral count")
    ax2.set_ylabel("peripheral eigenvalues (count)", color="tab:red")
    ax[2].legend(loc="lower left", fontsize=8)
    ax[2].set_xlabel("r")
    for a in ax:
        for x, name in ((7 - 4 * np.sqrt(3), "7-4sqrt3"), (3 - 2 * np.sqrt(2), "3-2sqrt2")):
            if rmin <= x <= rmax:
                a.axvline(x, color="k", lw=1, ls="--")
        for n, lo, hi in zip(w["n"], w["lower"], w["upper"]):
            hi = hi if np.isfinite(hi) else lo
            if hi >= rmin and lo <= rmax:
                a.axvspan(max(lo, rmin), min(hi, rmax), color="tab:blue", alpha=0.12, lw=0)
    ax[0].text(7 - 4 * np.sqrt(3), 1.0, " 7-4sqrt3", fontsize=8, va="bottom")
    ax[0].text(3 - 2 * np.sqrt(2), 1.0, " 3-2sqrt2", fontsize=8, va="bottom")
    ax[0].set_title(f"Ulam operator of P_r across r: {boxes} boxes (strip), {samples} samples per box, {len(r)} r values\n"
                    f"dashed: 7-4sqrt3, 3-2sqrt2; shaded: windows [root of Q_n, r_crit,2(n)] of (ab)^n(cb)^n, n = 2..12")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
