#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the number of feasible periodic words (stable and unstable) of length <= L against r.

Usage: patterns_feasible.py NAME.h5 OUT.png
Reads NAME.h5 alone (written by `btob pattern atlas --feasible`, NAME = feasible by default): the counts count_r,
count_stable, count_unstable, count_feasible, count_stable_collapse, count_unstable_collapse (the columns of
NAME_counts.csv) and the attributes max_length, words_scanned, feasible_words; writes OUT.png atomically.  Left: the
counts over (0, 1) on a log scale; right: a zoom on 0.15 <= r <= 0.6 with r_crit ~ 0.1917 (the earlier literature's
bound) and 2^(2/3) - 1 (no collapse above).
"""

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs
import matplotlib.pyplot as plt  # noqa: E402


def draw(f):
    """The figure of an h5py-like f (the datasets and attributes `btob pattern atlas --feasible` writes)."""
    meta = attrs(f)
    r = [float(x) for x in f["count_r"][()]]
    st, un, tot, stc, unc = ([int(x) for x in f["count_" + k][()]]
                             for k in ("stable", "unstable", "feasible", "stable_collapse", "unstable_collapse"))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, (x0, x1) in zip(axes, [(0.0, 1.0), (0.15, 0.6)]):
        ax.axvspan(0, 0.02, color="0.9", lw=0)  # not scanned
        ax.step(r, tot, where="mid", color="black", lw=1.0, label="feasible (stable + unstable)")
        ax.step(r, un, where="mid", color="#d62728", lw=1.0, label="unstable only")
        ax.step(r, st, where="mid", color="#1f4fd6", lw=1.0, label="stable")
        ax.step(r, unc, where="mid", color="#ff9896", lw=1.6, ls="--", label="unstable, and a collapse of four particles")
        ax.step(r, stc, where="mid", color="#17becf", lw=1.6, ls="--", label="stable, and a collapse of four particles")
        ax.axvline(0.1917, color="gray", ls="--", lw=0.8)
        ax.text(0.1917, 0.97, " r_crit ~ 0.1917", transform=ax.get_xaxis_transform(), fontsize=7, va="top")
        ax.axvline(2 ** (2 / 3) - 1, color="gray", ls=":", lw=0.8)
        ax.text(2 ** (2 / 3) - 1, 0.90, " 2^(2/3)-1", transform=ax.get_xaxis_transform(), fontsize=7, va="top")
        ax.set_xlim(x0, x1)
        ax.set_yscale("symlog", linthresh=1)
        ax.set_ylim(bottom=0)
        ax.set_xlabel("restitution coefficient r (dimensionless)")
        ax.set_ylabel("number of canonical words with a feasible periodic point")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="center right", fontsize=8)
    axes[1].set_title("zoom 0.15 <= r <= 0.6", fontsize=9)
    L = meta.get("max_length", "?")
    fig.suptitle(f"Periodic patterns of P_r, stable or unstable: canonical primitive words of length <= {L}\n"
                 f"({meta.get('words_scanned', '?')} scanned, {meta.get('feasible_words', '?')} feasible for some r); "
                 f"counts at r = 0.001, ..., 0.999 (grey: r < 0.02, not scanned)\n"
                 f"dashed: the periodic orbits four particles can follow in a collapse (K_w real on the orbit's plane)",
                 fontsize=9)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    plotlib.main(draw)
