# SPDX-License-Identifier: GPL-3.0-or-later
"""Figures 7.1-7.8: eigenvalues (when real) and moduli of a word's period matrix against r, and the feasibility
quantities of its tracked eigenvector.  Usage: pattern_curves.py RESULT.h5 OUTDIR (reads only the HDF5 file: the
critical r values are its critical_r and critical_what)
Writes the paper's figures for 132312 (7.1-7.5) and 13223122 (7.6-7.8), or generic names for other words."""
import os
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np

from plotlib import attrs, save_atomic

# The paper's figures: (file, kind, zoom r_max of panel (b), [(feas column, label), ...]).
PAPER = {
    "132312": {
        "matrix": "J P2 P3 P1", "fig": [
            ("fig7_1", "eig", 0.19, None), ("fig7_2", "mod", 0.3, None),
            ("fig7_3", "feas", None, [("u_z", "1st: $(u)_z$"), ("ay-x(v0)", r"2nd: $\alpha (u)_y - (u)_x$")]),
            ("fig7_4", "feas", None, [("y(v1)", "3rd: $(P_1 u)_y$"), ("ay-z(v1)", r"4th: $\alpha (P_1 u)_y - (P_1 u)_z$")]),
            ("fig7_5", "feas", None, [("ay-x(v2)", r"5th: $\alpha (P_3 P_1 u)_y - (P_3 P_1 u)_x$"),
                                      ("ay-z(v2)", r"6th: $\alpha (P_3 P_1 u)_y - (P_3 P_1 u)_z$")])]},
    "132^2312^2": {
        "matrix": "J P2 P2 P3 P1", "fig": [
            ("fig7_6", "eig", 0.3, None), ("fig7_7", "mod", 0.3, None),
            ("fig7_8", "feas", None, [("u_z", "1st: $(u)_z$"), ("ay-x(v0)", r"2nd: $\alpha (u)_y - (u)_x$")])]},
}


def symlog_ticks(ax, lin, lo, hi):
    """Ticks 0 and +-10^k for the decades above the linear band that fit in [lo, hi], at most five per sign: the
    default locator labels +-lin as well, and those labels overlap 0's."""
    def decades(top):
        if top <= lin:
            return []
        ks = np.arange(np.ceil(np.log10(lin)) + 1, np.floor(np.log10(top)) + 1)
        step = max(1, int(np.ceil(len(ks) / 5)))
        return [10.0 ** k for k in ks[::-1][::step]]
    ticks = sorted([-t for t in decades(-lo)] + [0.0] + decades(hi))
    ax.set_yticks(ticks)
    ax.yaxis.set_minor_locator(plt.NullLocator())

def robust_ylim(y, x, lo_r=None):
    """A y range holding the curve away from its poles: the 1..99 percentiles, widened by 15%; returns
    (lo, hi, n_clipped)."""
    f = np.isfinite(y)
    if lo_r is not None:
        f &= x >= lo_r
    if not f.any():
        return -1, 1, 0
    a, b = np.percentile(y[f], [1, 99])
    a, b = min(a, 0), max(b, 0)
    pad = 0.15 * (b - a if b > a else 1)
    lo, hi = a - pad, b + pad
    return lo, hi, int(((y < lo) | (y > hi)).sum())


def main(h5path, outdir):
    with h5py.File(h5path, "r") as f:
        a = attrs(f)
        r = f["r"][()]
        re, im, mod = f["eig_re"][()], f["eig_im"][()], f["modulus"][()]
        feas = f["feas"][()]
        critical = list(zip(f["critical_what"].asstr()[()], f["critical_r"][()]))
    names = a["feas_names"].split(",")
    word = a["word"]
    # Sign changes where long double does not resolve the eigenvector are not drawn; the subtitle counts them.
    crit = [(what, float(rc)) for what, rc in critical if not what.startswith("undecided")]
    undecided = [float(rc) for what, rc in critical if what.startswith("undecided")]
    spec = PAPER.get(word, {"matrix": "A", "fig": [(f"{a['name']}_eig", "eig", 0.3, None),
                                                     (f"{a['name']}_mod", "mod", 0.3, None),
                                                     (f"{a['name']}_feas", "feas", None,
                                                      [(n, n) for n in names[:2]])]})
    reduced = "J M_h" if int(a["reduced"]) else "M_w"
    sub = (f"word {word}, matrix {spec['matrix'] if word in PAPER else reduced}; {len(r)} values of r; "
           f"spectrum in long double" + (f"; {len(undecided)} sign changes of $u_x u_z$ undecided in long double "
                                         f"(r <= {max(undecided):.4g}), not drawn" if undecided else ""))

    def vlines(ax, only=None):
        for what, rc in crit:
            if only and what not in only:
                continue
            style = {"u_x = 0": ("red", "-"), "dominance": ("red", "--"), "u_z = 0": ("purple", ":")}[what]
            ax.axvline(rc, color=style[0], ls=style[1], lw=0.9)

    def legend_crit(ax):
        from matplotlib.lines import Line2D
        h = []
        kinds = {w for w, _ in crit}
        if "u_x = 0" in kinds:
            h.append(Line2D([], [], color="red", ls="-", label="$u_x = 0$: " + ", ".join(f"{c:.6f}" for w, c in crit if w == "u_x = 0")))
        if "dominance" in kinds:
            h.append(Line2D([], [], color="red", ls="--", label="tracked eigenvalue stops/starts dominating: "
                            + ", ".join(f"{c:.6f}" for w, c in crit if w == "dominance")))
        if "u_z = 0" in kinds:
            h.append(Line2D([], [], color="purple", ls=":", label="$u_z = 0$: " + ", ".join(f"{c:.6f}" for w, c in crit if w == "u_z = 0")))
        return h

    colours = ["tab:blue", "tab:orange", "tab:green"]
    for stem, kind, zoom, cols in spec["fig"]:
        if kind in ("eig", "mod"):
            fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
            for ax, rmax in zip(axes, (1.0, zoom)):
                sel = r <= rmax
                for j in range(3):
                    if kind == "eig":
                        y = np.where(im[:, j] == 0, re[:, j], np.nan)  # real eigenvalues only (the paper's plot)
                    else:
                        y = mod[:, j]
                    ax.plot(r[sel], y[sel], ".", ms=1.6, color=colours[j],
                            label=["lowest real root", "second real root (or complex pair)", "third real root (or complex pair)"][j])
                ax.axhline(0, color="0.7", lw=0.6)
                vlines(ax, only=("dominance",))
                ax.set_xlim(0, rmax)
                ax.set_xlabel("restitution coefficient $r$")
                ax.set_ylabel("eigenvalue (when real)" if kind == "eig" else "modulus of the eigenvalue")
                if kind == "mod":
                    ax.set_yscale("log")
                ax.set_title(("(a) " if rmax == 1.0 else "(b) ") + f"$0 \\leq r \\leq {rmax:g}$", fontsize=10)
            axes[0].legend(handles=[h for h in legend_crit(axes[0]) if "dominating" in h.get_label()]
                           + axes[0].get_legend_handles_labels()[0], fontsize=7, loc="best", markerscale=4)
            what = "Eigenvalues (when real)" if kind == "eig" else "Moduli of the eigenvalues (log scale)"
            fig.suptitle(f"Figure {stem[3]}.{stem[5:]}: {what} of the period matrix as functions of r\n{sub}",
                         fontsize=10)
        else:
            fig, axes = plt.subplots(len(cols), 1, figsize=(11, 3.4 * len(cols)), constrained_layout=True)
            for ax, (col, label) in zip(np.atleast_1d(axes), cols):
                y = feas[:, names.index(col)]
                lo, hi, clipped = robust_ylim(y, r)
                ax.plot(r, y, ".", ms=1.6, color="tab:blue")
                ax.axhline(0, color="0.4", lw=0.8)
                vlines(ax)
                # symlog: the sign (what the inequality asks) and the size both readable on one axis.  The linear
                # band |y| < lin is set below the curve's smallest size away from its sign changes (one decade under
                # the 1% quantile), so a curve crosses it only where it changes sign: a curve passing from the log
                # part into the linear band would bend there for no reason of its own.
                ay = np.abs(y[np.isfinite(y) & (y != 0)])
                lin = 10.0 ** np.floor(np.log10(max(float(np.percentile(ay, 1)), 1e-12)) - 1) if ay.size else 1e-3
                ax.set_yscale("symlog", linthresh=lin)
                lo, hi = lo * (2 if lo < 0 else 1), hi * 2
                ax.set_ylim(lo, hi)
                symlog_ticks(ax, lin, lo, hi)
                clipped = int(((y < lo) | (y > hi)).sum())
                # Sign changes away from the pole u_x = 0 (grid resolution, linear interpolation).
                dr = r[1] - r[0]
                poles = [c for w, c in crit if w == "u_x = 0"]
                for i in np.nonzero(np.isfinite(y[:-1]) & np.isfinite(y[1:]) & (np.sign(y[:-1]) != np.sign(y[1:])))[0]:
                    if any(abs(r[i] - c) < 3 * dr for c in poles):
                        continue
                    rz = r[i] - y[i] * dr / (y[i + 1] - y[i])
                    ax.plot([rz], [0], "kv", ms=6)
                    nz = getattr(ax, "_nz", 0)
                    ax._nz = nz + 1
                    ax.annotate(f"0 at r = {rz:.4f}", (rz, 0), textcoords="offset points", xytext=(4, 8 + 14 * (nz % 2)),
                                fontsize=8)
                ax.set_xlim(-0.01, 1.01)
                ax.set_xlabel("restitution coefficient $r$")
                ax.set_ylabel("value, $u_x = 1$ (symlog)")
                note = f"; {clipped} of {len(r)} points beyond the y range (near the pole $u_x = 0$)" if clipped else ""
                ax.set_title(f"{label} inequality{note}", fontsize=10)
                ax.legend(handles=legend_crit(ax), fontsize=7, loc="best")
            track = "dominant eigenvalue" if a["track"] == "dominant" else "negative real eigenvalue (real for every r)"
            fig.suptitle(f"Figure {stem[3]}.{stem[5:]}: feasibility inequalities along the word, eigenvector of the {track}"
                         f"\n{sub}", fontsize=10)
        save_atomic(fig, os.path.join(outdir, stem + ".png"))
        plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
