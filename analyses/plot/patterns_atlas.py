#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the atlas of stable periodic patterns against r, with the iterator's detections overlaid.

Usage: patterns_atlas.py NAME.h5 OUT.png
Reads NAME.h5 alone (written by `btob pattern atlas`, NAME = atlas by default): the atlas's intervals (word, r_low,
r_high), the found patterns longer than L (long_word, long_r_low, long_r_high), the iterator's detections
(detected_word, detected_r, detected_status) and the check's attributes; writes OUT.png atomically (temporary file,
then rename).  One horizontal bar per pattern; when there are more than MAX_ROWS patterns, the ones with the widest
windows are shown (and the title says so), plus every pattern the iterator found.
"""

import plotlib  # noqa: E402  (main: the command line)
from plotlib import attrs, texts
import matplotlib.pyplot as plt  # noqa: E402

MAX_ROWS = 40


def is_text(d):
    return d.dtype.kind in "OSU" if hasattr(d, "dtype") else all(isinstance(t, str) for t in d)


def table(f, columns):
    """The table whose columns are the datasets `columns` (key: dataset) as a list of dicts; [] when absent (an
    atlas without the iterator check has no detected_* datasets)."""
    if any(name not in f for name in columns.values()):
        return []
    cols = {k: texts(f, name) if is_text(f[name]) else [float(x) for x in f[name][()]] for k, name in columns.items()}
    return [dict(zip(cols, values)) for values in zip(*cols.values())]


def draw(f):
    """The figure of an h5py-like f (the datasets and attributes `btob pattern atlas` writes)."""
    atlas = table(f, {"word": "word", "r_low": "r_low", "r_high": "r_high"})
    long_windows = table(f, {"word": "long_word", "r_low": "long_r_low", "r_high": "long_r_high"})
    detected = table(f, {"word": "detected_word", "r": "detected_r", "status": "detected_status"})
    meta = attrs(f)
    intervals = {}
    for row in atlas:
        intervals.setdefault(row["word"], []).append((float(row["r_low"]), float(row["r_high"])))
    width = {w: sum(h - lo for lo, h in iv) for w, iv in intervals.items()}
    for row in long_windows:
        intervals.setdefault(row["word"], []).append((float(row["r_low"]), float(row["r_high"])))
    found_words = {row["word"] for row in detected}
    ranked = sorted(width, key=lambda w: -width[w])
    shown = ranked[:MAX_ROWS]
    for w in ranked[MAX_ROWS:]:
        if w in found_words:
            shown.append(w)
    # Patterns found by the iterator that are longer than L (not in the atlas) get their own rows.
    long_found = sorted({row["word"] for row in detected if row["status"].startswith("longer")} - set(shown))
    # Symbol-periodic sequences the analysis does not call stable (neutral rotations in the P2 region).
    other = sorted({row["word"] for row in detected} - set(shown) - set(long_found))
    rows = long_found + sorted(shown, key=lambda w: min(lo for lo, _ in intervals[w])) + other
    fig, axes = plt.subplots(1, 2, figsize=(14, max(4.5, 0.28 * len(rows) + 1.8)), sharey=True,
                             gridspec_kw={"width_ratios": [1, 1.4]})
    for ax, (x0, x1) in zip(axes, [(0, 1), (0.07, 0.27)]):
        draw_panel(ax, rows, intervals, detected, found_words, x0, x1)
    axes[0].set_ylabel("pattern (1 = ab, 3 = cb, 2 = acb/cab), canonical up to rotation and J")
    axes[1].set_title("zoom on r in [0.07, 0.27]", fontsize=9)
    n_words = len(width)
    L = meta.get("max_length", "?")
    title = (f"Stable periodic patterns of P_r, r in (0, 1), words up to L = {L} symbols "
             f"({n_words} with a window")
    if n_words > MAX_ROWS:
        title += f"; the {MAX_ROWS} widest shown, plus those the iterator found"
    title += ")"
    if detected:
        title += (f"\niterator: {meta.get('check_ics', '?')} random points x {meta.get('check_r_values', '?')} r values "
                  f"(Table 6.1), {meta.get('check_iterations', '?')} iterations, last {meta.get('check_tail', '?')} "
                  f"symbols; top rows: symbol-periodic but no sink (word 2: P2 rotation); bottom rows: found patterns longer than L")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def draw_panel(ax, rows, intervals, detected, found_words, x0, x1):
    for i, w in enumerate(rows):
        for lo, hi in intervals.get(w, []):
            ax.barh(i, hi - lo, left=lo, height=0.6, color="#1f4fd6" if w in found_words else "#9ab0e6")
    label_done = set()
    for row in detected:
        w = row["word"]
        if w not in rows:
            continue
        i = rows.index(w)
        r = float(row["r"])
        ok = row["status"] in ("stable in atlas", "longer than L: stable (verdict)")
        quasi = row["status"].startswith("quasi-periodic")
        key = "agree" if ok else ("quasi" if quasi else "disagree")
        style = {"agree": ("o", "#2ca02c", "iterator: periodic, stable in analysis"),
                 "quasi": ("s", "#17becf", "iterator: symbol-periodic on invariant curves (neutral, e.g. word 2)"),
                 "disagree": ("x", "#d62728", "iterator: symbol-periodic, NOT stable in analysis")}[key]
        ax.plot(r, i, marker=style[0], color=style[1], ms=5, ls="none", label=None if key in label_done else style[2])
        label_done.add(key)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels(rows, fontsize=7)
    ax.set_xlabel("restitution coefficient r (dimensionless)")
    ax.set_xlim(x0, x1)
    ax.set_ylim(-1, len(rows))
    ax.grid(axis="x", alpha=0.3)
    if x0 > 0:  # one legend, in the zoom panel's empty lower-left corner; the bars' two shades explained too
        from matplotlib.patches import Patch
        handles, _ = ax.get_legend_handles_labels()
        handles = [Patch(color="#1f4fd6", label="stability window (analysis) of a pattern the iterator found"),
                   Patch(color="#9ab0e6", label="stability window of a pattern the iterator did not find\n"
                                                "(no Table 6.1 r inside it, or a basin missed by the random points)")] + handles
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=2, fontsize=7, frameon=False)


if __name__ == "__main__":
    plotlib.main(draw, dpi=130)
