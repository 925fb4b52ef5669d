#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws C_N(phi, psi; n) against the lag n (linear, and log |C_N| with the window envelope, the noise floor
and the fitted decay) and the power spectrum, from a `btob correlate` HDF5 file.
Usage: stats_correlation.py DATA.h5 OUT.png"""

import matplotlib

import plotlib  # noqa: E402,F401  (Agg for the command line; a Python session keeps its backend)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    c = f["C_N"][...]
    env = f["envelope"][...]
    freq, ps = f["spectrum_frequency"][...], f["power_spectrum"][...]
    a = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    n = np.arange(len(c))
    obs = a["observables"].split(",")
    label = obs[0] if obs[0] == obs[1] else f"{obs[0]}, {obs[1]}"
    fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(16, 4.8), dpi=120)
    shown = min(len(c), 201)  # the first 200 lags resolve the oscillation; the log panel shows all lags
    ax.plot(n[:shown], c[:shown], lw=0.7, marker=".", ms=3)
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("lag n (map iterations)")
    ax.set_ylabel(rf"$C_N({label};\,n)$ (units of the observables squared)")
    ax.set_title(f"C_N against n, lags 0..{shown - 1} (all {len(c) - 1} lags on the right)", fontsize=9)

    # Dots, not a line: a periodic C_N alternates between O(1) and rounding-level zeros, and a line joining
    # them fills the panel.  Lags far below the noise floor (rounding level) are counted, not drawn.
    ac = np.abs(c[1:])
    floor_draw = a["noise_floor"] / 1e3
    keep = ac >= floor_draw
    bx.semilogy(n[1:][keep], ac[keep], ".", ms=2, color="C0", label=r"$|C_N(n)|$ (one dot per lag)")
    hidden = int((~keep).sum())
    w = int(round((len(c) - 1) / max(len(env), 1))) if len(env) else 1
    if len(env):
        centres = 1 + w * np.arange(len(env)) + 0.5 * (w - 1)
        bx.semilogy(centres, env, "o-", ms=2.5, lw=0.8, color="C1", label=f"envelope (max over {w} lags)")
    bx.axhline(a["noise_floor"], color="grey", ls="--", lw=0.8, label=r"noise floor $4|C_N(0)|/\sqrt{N}$")
    if "decay_rate" in a and a["decay_windows"] >= 3:
        nfit = np.linspace(1, 1 + w * a["decay_windows"], 50)
        bx.semilogy(nfit, a["envelope_first"] * np.exp(-a["decay_rate"] * (nfit - nfit[0])), "k:", lw=1.2,
                    label=f"fit: rate {a['decay_rate']:.3g} ± {a['decay_rate_error']:.2g} /iteration "
                          f"({a['decay_verdict']})")
    bx.set_ylim(bottom=floor_draw / 2)
    if hidden:
        bx.text(0.99, 0.02, f"{hidden} of {len(ac)} lags have |C_N| < noise floor / 1000 (rounding level): not drawn",
                transform=bx.transAxes, ha="right", va="bottom", fontsize=7)
    bx.set_xlabel("lag n (map iterations)")
    bx.set_ylabel(r"$|C_N(n)|$")
    title = f"log |C_N|: envelope {a['envelope_min']:.3g} .. {a['envelope_max']:.3g}"
    if "decay_verdict" in a:  # the fit's verdict and where |C_N| met the noise floor (btob correlate)
        title += f"; {a['decay_verdict']}"
        title += (f", floor at lag {a['decay_floor_lag']}" if "decay_floor_lag" in a
                  else f", floor not reached by lag {a['decay_fit_lags']}")
    bx.set_title(title, fontsize=9)
    bx.legend(fontsize=7, loc="center left", framealpha=0.9, markerscale=3)

    cx.semilogy(freq, ps + 1e-300, lw=0.6)
    cx.set_xlabel("frequency (cycles per map iteration)")
    cx.set_ylabel(f"periodogram of {obs[0]} (power per frequency bin)")
    cx.set_title(f"power spectrum; peak at {a['spectrum_peak_frequency']:.6g} cycles/iteration", fontsize=9)
    extra = f", FFT vs direct {a['max_rel_diff_fft_direct']:.1e} rel." if "max_rel_diff_fft_direct" in a else ""
    fig.suptitle(f"C_N({label}; n) at r = {a['r']}, x0 = ({a['point']}), N = {a['N']:.0e}, n ≤ {a['n_max']}, "
                 f"transient {a['transient']}, method {a['method']}, {a['scalar_type']}{extra}", fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
