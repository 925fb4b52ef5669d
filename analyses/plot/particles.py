#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Space-time diagram and animation of four particles collapsing along a periodic pattern.

Usage: particles.py NAME.h5 DIR
Reads NAME.h5 alone (written by `btob particles`): the events event_period, event_time, event_time_to_collapse,
event_x (x1..x4), event_letter (the start of each period and every collision of the first periods, positions in the
centre-of-mass frame, unit |p0|; time to collapse NaN without a collapse; events.csv is the same table) and the
attributes; writes DIR/spacetime.png and DIR/animation.gif (Pillow writer) atomically.
Between events the particles fly freely: positions are linear in time, hence in the time to collapse tau.
"""
import math
import os
import sys

import h5py

from plotlib import attrs, save_atomic
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402

COLORS = ["#1f4fd6", "#2ca02c", "#d62728", "#9467bd"]


def read(h5_path):
    with h5py.File(h5_path, "r") as f:
        letters = [t.decode() if isinstance(t, bytes) else str(t) for t in f["event_letter"][()]]
        ev = [dict(period=int(p), t=float(t), tau=float(tau), x=[float(v) for v in x], letter=letter)
              for p, t, tau, x, letter in zip(f["event_period"][()], f["event_time"][()],
                                              f["event_time_to_collapse"][()], f["event_x"][()], letters)]
        meta = attrs(f)
    collapse = all(math.isfinite(e["tau"]) for e in ev)
    if not collapse:  # no collapse: the time axis is the time before the last recorded collision
        t_end = ev[-1]["t"]
        for e in ev:
            e["tau"] = t_end - e["t"]
    return ev, meta, collapse


def positions_at(ev, tau):
    """Positions at time to collapse tau, linear between the two events around it (tau decreases)."""
    for a, b in zip(ev, ev[1:]):
        if a["tau"] >= tau >= b["tau"]:
            s = 0.0 if a["tau"] == b["tau"] else (a["tau"] - tau) / (a["tau"] - b["tau"])
            return [xa + s * (xb - xa) for xa, xb in zip(a["x"], b["x"])], a
    return ev[-1]["x"], ev[-1]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: particles.py NAME.h5 DIR")
    folder = sys.argv[2]
    ev, meta, collapse = read(sys.argv[1])
    rho, tq = float(meta["length_contraction"]), float(meta["time_contraction"])
    gamma = math.log(rho) / math.log(tq) if 0 < tq < 1 and 0 < rho < 1 else 1.0
    title = (f"{meta['word']} at r = {meta['r']:g}: letters {meta['letters']} per period; {meta['periods_ok']} of "
             f"{meta['periods']} periods reproduced ({meta['scalar_type']})\n")
    if collapse:
        title += (f"per period: lengths x{rho:.6g}, times x{tq:.6g}; collapse after "
                  f"{float(meta['time_to_collapse']):.6g} |p0|/|q0|")
    else:
        why = meta["failure"].split("; ")[-1]
        title += (f"NO collapse along the pattern: the particles leave it after {meta['periods_ok']} whole periods "
                  f"({why}); the time axis ends at the last collision drawn")

    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    n_periods = max(e["period"] for e in ev) + 1
    for k, ax in enumerate(axes):
        scaled = k == 1
        for i in range(4):
            ts, xs = [], []
            for a, b in zip(ev, ev[1:]):
                for j in range(16):
                    s = j / 16
                    tau = a["tau"] + s * (b["tau"] - a["tau"])
                    x = a["x"][i] + s * (b["x"][i] - a["x"][i])
                    if tau <= 0:
                        continue
                    ts.append(tau)
                    if scaled and not collapse:
                        spread = (a["x"][3] - a["x"][0]) + s * ((b["x"][3] - b["x"][0]) - (a["x"][3] - a["x"][0]))
                        xs.append(x / spread)
                    else:
                        xs.append(x / tau ** gamma if scaled else x)
            ax.plot(ts, xs, color=COLORS[i], lw=1.0, label=f"particle {i + 1}")
        for k_e, e in enumerate(ev):
            if e["letter"] == "start" or e["tau"] <= 0:
                continue
            j = "abc".index(e["letter"])
            x = e["x"][j]
            y = (x / (e["x"][3] - e["x"][0]) if not collapse else x / e["tau"] ** gamma) if scaled else x
            ax.plot(e["tau"], y, "k.", ms=3)
            # Letters of one period alternate above and below their point (successive collisions are close).
            ax.annotate(e["letter"], (e["tau"], y), fontsize=7, xytext=(0, 5 if k_e % 2 else -10),
                        textcoords="offset points", ha="center")
        ax.set_xscale("log")
        ax.invert_xaxis()
        ax.set_xlabel(("time to collapse t* - t" if collapse else "time before the last recorded collision") +
                      "\n(units |p0|/|q0|, log scale; time runs to the right)")  # two lines: one was cut off
        if scaled and not collapse:
            ax.set_ylabel("x_i / (x_4 - x_1), positions rescaled by their spread")
            ax.set_title("rescaled configuration", fontsize=9)
        elif scaled:
            ax.set_ylabel(f"x_i / (t* - t)^gamma, gamma = ln(rho)/ln(time ratio) = {gamma:.4f}")
            ax.set_title("self-similar coordinates: the pattern repeats every period", fontsize=9)
        else:
            ax.set_ylabel("position x_i (units |p0|, centre-of-mass frame" + ("; collapse at 0)" if collapse else ")"))
            ax.set_title(f"positions, first {n_periods} periods, each collision marked with its letter", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    save_atomic(fig, os.path.join(folder, "spacetime.png"))
    plt.close(fig)

    # Animation: the configuration rescaled by its spread, tau log-uniform (about 24 frames per period).
    anim_periods = min(n_periods, 3)
    last = [e for e in ev if e["period"] < anim_periods]
    tau0 = last[0]["tau"]
    tau1 = min(e["tau"] for e in last if e["tau"] > 0)
    frames = 24 * anim_periods
    taus = [tau0 * (tau1 / tau0) ** (k / (frames - 1)) for k in range(frames)]
    fig, ax = plt.subplots(figsize=(6.4, 2.4), dpi=80)
    dots = [ax.plot([], [], "o", color=COLORS[i], ms=12)[0] for i in range(4)]
    text = ax.text(0.02, 0.92, "", transform=ax.transAxes, fontsize=8, va="top")
    ax.set_xlim(-0.85, 0.85)
    ax.set_ylim(-1, 1)
    ax.set_yticks([])
    ax.axhline(0, color="gray", lw=0.5)
    ax.set_xlabel("x_i / (x_4 - x_1): the configuration rescaled by its spread")
    ax.set_title(f"{meta['word']} at r = {meta['r']:g}: {anim_periods} periods, time to collapse log-uniform", fontsize=8)
    fig.tight_layout()

    def draw(k):
        x, a = positions_at(ev, taus[k])
        spread = x[3] - x[0]
        for i in range(4):
            dots[i].set_data([x[i] / spread], [0])
        last_letter = a["letter"] if a["letter"] != "start" else "b"
        text.set_text(f"period {a['period']}, last collision {last_letter}, t* - t = {taus[k]:.3g}, "
                      f"spread {spread:.3g}")
        return dots + [text]

    anim = animation.FuncAnimation(fig, draw, frames=frames, blit=False)
    dst = os.path.join(folder, "animation.gif")
    tmp = f"{dst}.tmp-{os.getpid()}.gif"
    anim.save(tmp, writer=animation.PillowWriter(fps=12))
    os.replace(tmp, dst)
    plt.close(fig)


if __name__ == "__main__":
    main()
