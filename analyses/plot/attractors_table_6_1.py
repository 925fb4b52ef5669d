# SPDX-License-Identifier: GPL-3.0-or-later
"""Table 6.1 against candidate initial distributions (analyses/table_6_1_candidates.py): the paper's counts out of ten
against each candidate's expected count with its 95% predictive interval, the rows' p-values and the table's
log-likelihood per candidate; and the detection check (the paper's pixel rule against btob's classifier).
Usage: attractors_table_6_1.py DIR   (reads DIR/*.csv and the manifest, writes DIR/table_6_1_candidates.png and
DIR/detection.png)
An analysis's figures (its tables against the paper's), not one command's: it reads the analysis's CSV files and
manifest as that script writes them."""
import csv
import json
import os
import sys

import numpy as np
from matplotlib import pyplot as plt

from plotlib import save_atomic

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def shown_candidates(like, manifest):
    """The candidates drawn in the panels over r: the best, the sphere measure, then those the manifest names."""
    order = sorted(like, key=lambda x: -float(x["log_likelihood"]))
    names = [order[0]["candidate"]] + [n for n in manifest["shown"] if n != order[0]["candidate"]]
    return names[:len(COLOURS)]


def panel_counts(ax, rows, names, r_values):
    x = np.arange(len(r_values))
    paper = {float(x_["r"]): int(x_["paper_count"]) for x_ in rows}
    for i, name in enumerate(names):
        sel = {float(x_["r"]): x_ for x_ in rows if x_["candidate"] == name}
        off = (i - (len(names) - 1) / 2) * 0.13
        e = np.array([float(sel[r]["expected_count"]) for r in r_values])
        lo = np.array([float(sel[r]["count_low"]) for r in r_values])
        hi = np.array([float(sel[r]["count_high"]) for r in r_values])
        # the mean can sit just outside the integer quantiles when f is near 0 or 1: no negative bar
        ax.errorbar(x + off, e, yerr=[np.maximum(e - lo, 0), np.maximum(hi - e, 0)], fmt="o", ms=3.5, lw=1, capsize=1.5, color=COLOURS[i],
                    label=f"{name}: expected count, 95% predictive interval")
    ax.plot(x, [paper[r] for r in r_values], "D", color="black", ms=6, mfc="none", mew=1.5, label="paper (Table 6.1)")
    ax.set_ylabel("periodic orbits out of 10 (count)")
    ax.set_ylim(-0.5, 10.5)
    ax.set_yticks(range(0, 11, 2))
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(0, 1.01), ncol=3, frameon=False)


def panel_pvalues(ax, rows, names, r_values):
    x = np.arange(len(r_values))
    for i, name in enumerate(names):
        sel = {float(x_["r"]): x_ for x_ in rows if x_["candidate"] == name}
        p = np.array([max(float(sel[r]["p_value"]), 1e-12) for r in r_values])
        off = (i - (len(names) - 1) / 2) * 0.13
        ax.plot(x + off, p, "o", ms=3.5, color=COLOURS[i], label=name)
    ax.axhline(0.01, color="grey", ls="--", lw=1)
    ax.text(len(r_values) - 0.5, 0.012, "p = 0.01", ha="right", va="bottom", fontsize=7, color="grey")
    ax.set_yscale("log")
    ax.set_ylim(1e-8, 1.5)
    ax.set_ylabel("two-sided p-value of the paper's count")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{r:g}" for r in r_values], rotation=60, fontsize=8)
    ax.set_xlabel("restitution coefficient r (the rows of Table 6.1, equally spaced)")
    ax.grid(axis="y", alpha=0.3)


def panel_likelihood(ax, like):
    """One row per candidate: the table's log-likelihood with btob's classifier (bar) and with the paper's rule on
    the same candidate's orbits (cross), and the value typical of tables drawn from the candidate (+- 2 sd)."""
    by = {x["candidate"]: x for x in like}
    base = sorted((n for n in by if not n.endswith("+rule")),
                  key=lambda n: max(float(by[n]["log_likelihood"]), float(by.get(n + "+rule", by[n])["log_likelihood"])))
    y = np.arange(len(base))
    ll = np.array([float(by[n]["log_likelihood"]) for n in base])
    rule = np.array([float(by[n + "+rule"]["log_likelihood"]) if n + "+rule" in by else np.nan for n in base])
    mean = np.array([float(by[n]["expected_log_likelihood"]) for n in base])
    sd = np.array([float(by[n]["sd_log_likelihood"]) for n in base])
    left = -200.0
    ax.barh(y, np.maximum(ll, left), color="#9ecae1", label="btob's classifier")
    ax.plot(np.maximum(rule, left), y, "x", color="#d62728", ms=7, mew=1.5, label="paper's rule on the same orbits")
    ax.errorbar(mean, y, xerr=2 * sd, fmt="|", color="black", ms=9, lw=1,
                label="typical under the candidate\n(mean +- 2 sd, synthetic tables)")
    for yi, v in zip(y, ll):
        if v < left:
            ax.text(left * 0.9, yi, f"{v:.0f}", va="center", ha="left", fontsize=7)
    sat = float(like[0]["saturated_log_likelihood"])
    ax.axvline(sat, color="grey", ls=":", lw=1)
    ax.text(sat - 2, len(base) - 0.5, "each row at\nits own K/10", fontsize=7, color="grey", ha="right",
            va="bottom")
    ax.set_yticks(y)
    ax.set_yticklabels(base, fontsize=8)
    ax.set_ylim(-0.7, len(base) + 2.5)
    ax.set_xlim(left, 0)
    ax.set_xlabel("log-likelihood of Table 6.1 (natural log, 33 rows)")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(axis="x", alpha=0.3)


def draw_main(d):
    rows = read(os.path.join(d, "candidates.csv"))
    like = read(os.path.join(d, "likelihood.csv"))
    with open(os.path.join(d, "table_6_1_candidates.json")) as f:
        m = json.load(f)
    r_values = sorted({float(x["r"]) for x in rows})
    names = shown_candidates(like, m)
    fig = plt.figure(figsize=(15, 9), constrained_layout=True)
    gs = fig.add_gridspec(2, 2, width_ratios=[3, 1], height_ratios=[1.3, 1])
    a, b, c = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[:, 1])
    panel_counts(a, rows, names, r_values)
    a.set_xticks(np.arange(len(r_values)))
    a.set_xticklabels([])
    panel_pvalues(b, rows, names, r_values)
    panel_likelihood(c, like)
    fig.suptitle(f"Table 6.1 (10 orbits per r, {m['iterations']} iterations, last {m['tail']} plotted) against btob: "
                 f"{m['orbits']} orbits per r and candidate initial distribution classified by btob (transient "
                 f"{m['transient']}), {m['rule_orbits']} by the paper's rule; seed {m['seed']}\nbeta-binomial: "
                 "the count of 10 draws with btob's periodic fraction and its own uncertainty (uniform prior)",
                 fontsize=10)
    return fig


def draw_detection(d):
    rows = read(os.path.join(d, "detection.csv"))
    hist = read(os.path.join(d, "detection_histogram.csv"))
    with open(os.path.join(d, "table_6_1_candidates.json")) as f:
        m = json.load(f)
    fig, (a, b) = plt.subplots(1, 2, figsize=(15, 5.5), constrained_layout=True, gridspec_kw={"width_ratios": [1, 2]})
    edges = np.array([float(x["pixels_low"]) for x in hist] + [float(hist[-1]["pixels_high"])])
    for t, col in (("periodic", "#1f77b4"), ("quasi-periodic", "#17becf"), ("chaotic", "#8b0000"),
                   ("undecided", "black")):
        n = np.array([int(x[t.replace("-", "_")]) for x in hist])
        if n.sum():
            a.stairs(n, edges, label=f"btob: {t} ({n.sum()})", color=col, lw=1.5)
    n = np.array([int(x["rule_finite"]) for x in hist])
    a.stairs(n, edges, label=f"paper's rule: finite ({n.sum()})", color="black", ls="--", lw=1.2)
    a.axvline(m["finite_max_pixels"] + 0.5, color="grey", ls=":")
    a.text(m["finite_max_pixels"] * 1.1, 0.5, f"{m['finite_max_pixels']} pixels", fontsize=7, color="grey",
           va="center", transform=a.get_xaxis_transform())
    a.set_xscale("log")
    a.set_xlabel(f"distinct pixels among the last {m['tail']} of {m['iterations']} iterations\n"
                 f"(pixel {m['pixel_w1']:.4f} x {m['pixel_w2']:.4f} in (w1, w2): a 434 x 342 px plot of "
                 "[-2,2] x [-1,1])")
    a.set_ylabel("orbits (all r, all checked candidates)")
    a.legend(fontsize=7, loc="upper center")
    r_values = sorted({float(x["r"]) for x in rows})
    x = np.arange(len(r_values))
    paper = {float(x_["r"]): int(x_["paper_count"]) for x_ in read(os.path.join(d, "candidates.csv"))}
    for i, name in enumerate(dict.fromkeys(x_["candidate"] for x_ in rows)):
        sel = {float(x_["r"]): x_ for x_ in rows if x_["candidate"] == name}
        n = np.array([int(sel[r]["orbits"]) for r in r_values])
        off = (i - 0.5) * 0.25
        b.plot(x + off, 10 * np.array([int(sel[r]["btob_periodic"]) for r in r_values]) / n, "o", ms=4,
               color=COLOURS[i], label=f"{name}: btob's classifier")
        b.plot(x + off, 10 * np.array([int(sel[r]["rule_periodic"]) for r in r_values]) / n, "x", ms=6,
               color=COLOURS[i], label=f"{name}: paper's rule on the same orbits")
    b.plot(x, [paper[r] for r in r_values], "D", color="black", mfc="none", ms=6, mew=1.5, label="paper (Table 6.1)")
    b.set_xticks(x)
    b.set_xticklabels([f"{r:g}" for r in r_values], rotation=60, fontsize=8)
    b.set_xlabel("restitution coefficient r (the rows of Table 6.1, equally spaced)")
    b.set_ylabel("periodic orbits per 10 (btob: 10 x fraction)")
    b.set_ylim(-0.5, 10.5)
    b.grid(axis="y", alpha=0.3)
    b.legend(fontsize=7, loc="lower left", ncol=3)
    fig.suptitle(f"Detection rule: btob's classifier against the paper's on the same orbits ({m['check_orbits']} per r "
                 f"and candidate, seed {m['seed']}): the last {m['tail']} of {m['iterations']} iterations are finite "
                 f"when they form p <= {m['max_period']} dots of at most {m['blob_pixels']:g} pixels", fontsize=10)
    return fig


def main(d):
    save_atomic(draw_main(d), os.path.join(d, "table_6_1_candidates.png"))
    save_atomic(draw_detection(d), os.path.join(d, "detection.png"))


if __name__ == "__main__":
    main(sys.argv[1])
