# SPDX-License-Identifier: GPL-3.0-or-later
"""P2's invariant curves (btob leaves): at one r, where orbits land (label map and landing density with its bands,
the kernel estimator, the coarse histogram and the region's own law), the rotation number per leaf and the
Kolmogorov-Smirnov distances of the measure on a leaf; across r, theta / (2 pi) with the resonances l / m, the region's
measure and the landing mass, the landing law's moments and its density."""

import numpy as np
from matplotlib import pyplot as plt

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs


def _title(a, rows):
    where = f"r = {float(a['r_value']):g}" if rows == 1 else \
        f"r = {float(a['r_min']):g} .. {float(a['r_max']):g} ({rows} values)"
    # Two lines: on one, the title ran past both edges of the figure.
    return (f"P2's invariant curves (leaves): {where}; grid {a['grid']} ({a['measure']})\n"
            f"classifier transient {a['transient']}, window {a['window']}; leaves followed {a['leaf_iterations']} "
            f"iterations")


def _one_r(f, a, fig):
    ax = fig.subplots(2, 2)
    lab = np.ma.masked_less(f["label_map"][0], 0)
    x1, x2 = f[a["axis1_name"]][...], f[a["axis2_name"]][...]
    im = ax[0, 0].pcolormesh(x1, x2, lab, cmap="viridis", vmin=0, vmax=1, shading="auto", rasterized=True)
    fig.colorbar(im, ax=ax[0, 0], label="landing label t (white: not on a P2 curve)")
    ax[0, 0].set_xlabel(a["axis1"]), ax[0, 0].set_ylabel(a["axis2"])
    ax[0, 0].set_title(f"(i) label of the leaf each orbit lands on; on a P2 curve: {float(f['mass'][0]):.4f}", fontsize=9)
    t, tc = f["t"][...], f["t_coarse"][...]
    d = ax[0, 1]
    d.fill_between(t, f["density_low"][0], f["density_high"][0], step="mid", color="tab:blue", alpha=0.25,
                   label="95% Clopper-Pearson band")
    d.step(t, f["density"][0], where="mid", color="tab:blue", label="histogram")
    d.step(tc, f["density_coarse"][0], where="mid", color="tab:orange", ls="--", label="histogram, twice the bin")
    d.plot(t, f["kde"][0], "k.", ms=4, label="kernel density (second estimator)")
    d.plot(t, f["region_density"][0], color="tab:green", label="points starting on a leaf (closed form)")
    d.set_xlabel("leaf label t (1 = the leaf touching the P2 region's boundary)")
    d.set_ylabel("density (fraction of the measure per unit t)")
    d.set_title("(i) landing law of t", fontsize=9)
    d.legend(fontsize=7)
    lt, stays = f["leaf_t"][...], f["leaf_stays"][0].astype(bool)
    diff = np.abs(f["leaf_birkhoff"][0] - f["leaf_exact"][0])
    rr = ax[1, 0]
    rr.semilogy(lt[stays], np.maximum(diff[stays], 1e-17), "o", color="tab:blue", label="leaf inside the region")
    rr.semilogy(lt[~stays], np.maximum(diff[~stays], 1e-17), "x", color="tab:red", label="leaf leaving the region")
    rr.axvline(1, color="0.5", ls=":")
    rr.set_xlabel("leaf label t")
    rr.set_ylabel("|weighted Birkhoff - theta/2pi| (turns)")
    rr.set_title(f"rotation number: theta/2pi = {float(f['rotation'][0]):.10f}", fontsize=9)
    rr.legend(fontsize=7)
    k = ax[1, 1]
    for name, lab2, c in (("ks_uniform", "uniform eigen-angle", "tab:blue"), ("ks_strip", "arc length (strip)", "tab:orange"),
                          ("ks_sphere", "arc length (sphere)", "tab:green")):
        k.semilogy(lt[stays], f[name][0][stays], "o-", color=c, label=lab2)
    k.axhline(float(a["ks_critical"]), color="k", ls="--", label="95% KS scale 1.358/sqrt(n)")
    k.set_xlabel("leaf label t (leaves inside the region)")
    k.set_ylabel("Kolmogorov-Smirnov distance (1)")
    k.set_title("(ii) the measure on a leaf: eigen-angles of one orbit", fontsize=9)
    k.legend(fontsize=7)


def _across_r(f, a, fig):
    ax = fig.subplots(2, 2)
    r = f["r"][...]
    p = ax[0, 0]
    p.plot(r, f["rotation"][...], "k-", label="theta / (2 pi)")
    # Each resonance is the point (r(l/m), l/m) of the curve, labelled to its right at its own height l/m; a label
    # within 0.008 turns (about a label's height) of the last one drawn is left out, its dot stays.
    last = None
    for sr, l, m in sorted(zip(f["stripe_r"][...], f["stripe_l"][...], f["stripe_m"][...])):
        if r.min() <= sr <= r.max():
            p.plot(sr, l / m, "o", ms=4, color="tab:blue")
            if last is None or abs(l / m - last) > 0.008:
                p.annotate(f"{l}/{m}", (sr, l / m), xytext=(6, 0), textcoords="offset points", fontsize=8,
                           va="center", color="tab:blue")
                last = l / m
    p.set_xlabel("r"), p.set_ylabel("rotation number (turns/iteration)")
    p.set_title("(iv) rotation number of the leaves; blue dots: resonances theta/2pi = l/m (eq. (6.3))", fontsize=9)
    q = ax[0, 1]
    q.plot(r, f["region_share"][...], "g-", label="region t <= 1 (closed form)")
    q.errorbar(r, f["mass"][...], yerr=[f["mass"][...] - f["mass_low"][...], f["mass_high"][...] - f["mass"][...]],
               fmt="o", ms=3, color="tab:blue", label="orbits landing on a P2 curve (95%)")
    q.set_xlabel("r"), q.set_ylabel("fraction of the measure")
    q.set_title("(iv) region and landing mass", fontsize=9), q.legend(fontsize=7)
    m = ax[1, 0]
    m.errorbar(r, f["landing_mean"][...], yerr=f["landing_sd"][...], fmt="o", ms=3, label="landing t: mean +- sd")
    m.plot(r, f["region_mean"][...], "g-", label="mean t of the region's own measure")
    m.set_xlabel("r"), m.set_ylabel("leaf label t"), m.set_ylim(0, 1.05)
    m.set_title("(iv) moments of the landing law", fontsize=9), m.legend(fontsize=7)
    h = ax[1, 1]
    im = h.pcolormesh(r, f["t"][...], f["density"][...].T, shading="auto", cmap="magma", rasterized=True)
    fig.colorbar(im, ax=h, label="landing density (per unit t)")
    h.set_xlabel("r"), h.set_ylabel("leaf label t")
    h.set_title("(iv) landing density across r", fontsize=9)


def draw(f):
    """The figure (returned, not saved) from an h5py-like f: an h5py.File, or a btob Python result (btob.plotting)."""
    a = attrs(f)
    rows = int(f["r"].shape[0])
    fig = plt.figure(figsize=(13, 9.5), constrained_layout=True)
    (_one_r if rows == 1 else _across_r)(f, a, fig)
    fig.suptitle(a.get("title") or _title(a, rows), fontsize=10)
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
