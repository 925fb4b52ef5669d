# SPDX-License-Identifier: GPL-3.0-or-later
"""Convergence table of results/transfer: every `btob transfer` run's key numbers, grouped by r, three resolutions
each; runs without a spectrum (--eigenvalues 0: the basins alone) leave the spectral columns
empty.  Then the basins from the Ulam graph against the counted fractions of `btob basins` across the resolutions:
errors against the box side, their rate, and Richardson's extrapolation (basins_convergence.csv,
basins_extrapolation.csv, basins_convergence.png).
Usage: transfer_summary.py results/transfer  -> results/transfer/convergence.csv, ..."""
import csv
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "plot"))
from plotlib import save_atomic  # noqa: E402  (the plot scripts' atomic PNG write)


def expand(word):
    """A pattern with exponents (132^3312^3) as its plain word (1322231222), rotated to its smallest rotation."""
    out, i = "", 0
    while i < len(word):
        if word[i] == "^":
            j = i + 1
            while j < len(word) and word[j].isdigit():
                j += 1
            out += out[-1] * (int(word[i + 1:j]) - 1)
            i = j
        else:
            out += word[i]
            i += 1
    return min(out[k:] + out[:k] for k in range(len(out))) if out else out


def counted_fractions(root, r):
    """`btob basins` fractions at r (results/attractors/basins_rR/basins_fractions.csv), keyed like basins.csv's
    attractors: the expanded word of a periodic attractor, "P2 region" for the P2 invariant curves."""
    path = os.path.join(root, "..", "attractors", f"basins_r{r}", "basins_fractions.csv")
    if not os.path.exists(path):
        return {}
    out = {}
    for row in csv.DictReader(open(path)):
        if row["type"] == "periodic":
            out[expand(row["pattern"])] = (float(row["fraction"]), float(row["ci_low"]), float(row["ci_high"]))
        elif row["type"] == "quasi-periodic":
            out["P2 region"] = (float(row["fraction"]), float(row["ci_low"]), float(row["ci_high"]))
    return out


def main(root):
    rows, basin_rows = [], []
    for man in sorted(glob.glob(os.path.join(root, "r0.*_*", "transfer.json"))):
        d = os.path.dirname(man)
        a = json.load(open(man))
        # A run without a spectrum (eigenvalues 0) has neither table: its spectral columns are empty cells.
        spectral = int(a.get("eigenvalues", 1)) > 0
        spec = list(csv.DictReader(open(os.path.join(d, "spectrum.csv")))) if spectral else []
        comps = list(csv.DictReader(open(os.path.join(d, "components.csv")))) if spectral else []
        cyc_path = os.path.join(d, "cycles.csv")
        cycles = list(csv.DictReader(open(cyc_path))) if os.path.exists(cyc_path) and spectral else []
        bas_path = os.path.join(d, "basins.csv")
        basins = list(csv.DictReader(open(bas_path))) if os.path.exists(bas_path) else []
        counted = counted_fractions(root, a["r"])

        def key(b):
            return "P2 region" if b["attractor"] == "P2 region" else expand(b["attractor"])

        lam = [complex(float(s["re"]), float(s["im"])) for s in spec]
        beta = a.get("p2_beta")
        beta = float(beta) if beta not in (None, "nan") else float("nan")
        # The eigenvalue closest in argument to exp(i beta) among those of modulus > 0.9 (the first rotation mode).
        rot_mod, rot_arg_err = float("nan"), float("nan")
        if math.isfinite(beta):
            cand = [z for z in lam if abs(z) > 0.9 and abs(z.imag) > 1e-9]
            if cand:
                z = min(cand, key=lambda z: abs(abs(math.atan2(z.imag, z.real)) - beta))
                rot_mod, rot_arg_err = abs(z), abs(abs(math.atan2(z.imag, z.real)) - beta)
        row = {
            "r": a["r"], "boxes": a["boxes"], "samples": a["samples"], "nnz": a["nnz"],
            "matrix_MB": round(a["matrix_bytes"] / 1e6, 2), "seconds": round(a["seconds"], 2),
            "closed_classes": a["closed_classes"], "near_one_count": a.get("near_one_count", ""),
            "unit_circle_count": sum(1 for z in lam if abs(z) > 1 - 1e-9),
            "near_one_values": ";".join(f"{z.real:.6f}" for z in lam if abs(z.imag) < 1e-12 and abs(z - 1) <= 0.01),
            "above_0.99": sum(1 for z in lam if abs(z) > 0.99),
            "components": len(comps),
            "component_fractions": ";".join(f'{float(c["lebesgue_fraction"]):.4f}' for c in comps),
            "component_rho": ";".join(f'{float(c["rho"]):.6f}' for c in comps),
            "lambda_next_real": a.get("second_value", ""),
            "rotation_modulus": rot_mod, "rotation_arg_error": rot_arg_err,
            "cycle_radius99": ";".join(f'{c["word"]}:{c["radius99"]}' for c in cycles),
            "cycle_mass_3x3": ";".join(f'{c["word"]}:{float(c["mass_neighbourhood"]):.4f}' for c in cycles),
            "tv_boxes": a.get("tv_boxes", ""), "tv_32x32": a.get("tv_coarse", ""),
            # Basins from the Ulam graph against the counted fractions of `btob basins` (same Lebesgue rectangle);
            # an interval is written [lo hi], without a comma, so that the cell needs no quoting (tests/cli_csv.py)
            "basin_fractions": ";".join(f'{b["attractor"]}:{float(b["fraction"]):.4f}' for b in basins),
            "counted_fractions": ";".join(
                f'{b["attractor"]}:{counted[key(b)][0]:.4f}[{counted[key(b)][1]:.4f} {counted[key(b)][2]:.4f}]'
                for b in basins if key(b) in counted),
        }
        if not spectral:  # what needs eigenvectors was not computed
            for k in ("near_one_count", "unit_circle_count", "near_one_values", "above_0.99", "components",
                      "component_fractions", "component_rho", "lambda_next_real", "rotation_modulus",
                      "rotation_arg_error", "cycle_radius99", "cycle_mass_3x3", "tv_boxes", "tv_32x32"):
                row[k] = ""
        rows.append(row)
        for b in basins:
            if key(b) in counted:
                f, lo, hi = counted[key(b)]
                n = int(str(a["boxes"]).split("x")[0])
                basin_rows.append({"r": a["r"], "attractor": b["attractor"], "boxes": a["boxes"], "h": 1 / n,
                                   "fraction": float(b["fraction"]), "counted": f, "ci_low": lo, "ci_high": hi})
    rows.sort(key=lambda x: (float(x["r"]), int(str(x["boxes"]).split("x")[0])))
    out = os.path.join(root, "convergence.csv")
    write_csv(out, rows, list(rows[0].keys()))
    print(f"wrote {out} ({len(rows)} runs)")
    basin_convergence(root, basin_rows)
    gap_convergence(root)


def write_csv(path, rows, fields):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def cell(x, fmt="{:.6g}"):
    """A number as a CSV cell; not a finite number: an empty cell."""
    return fmt.format(x) if isinstance(x, (int, float)) and math.isfinite(x) else ""


def basin_convergence(root, basin_rows):
    """The basins from the Ulam graph against the counted fractions, per (r, attractor) across the box side h = 1/N
    (N x N boxes; halving h at each step):
      * basins_convergence.csv: h, the fraction, the counted fraction with its interval, the error and whether the
        fraction lies in the interval;
      * basins_extrapolation.csv: the rate p of |error| ~ h^p (least squares over all resolutions, and over the
        three finest), the observed order of the three finest without the counts, q = log2(|F(2h) - F(4h)| /
        |F(h) - F(2h)|), and Richardson's extrapolation from the two finest assuming the error ~ h (E = 2 F(h) -
        F(2h)) with the error estimate |E - E'| from the three finest (E' = 2 F(2h) - F(4h), the same extrapolation
        one resolution coarser); whether E and the band E +- |E - E'| meet the counted interval; and Aitken's
        extrapolation of the three finest (order q instead of 1; empty when their differences do not shrink
        geometrically);
      * basins_convergence.png: |error| against h on log axes, the counted intervals' half-widths as dotted lines."""
    import numpy as np
    if not basin_rows:
        return
    # Only where attractors coexist (a single attractor absorbs everything at every resolution: nothing converges).
    names = {}
    for b in basin_rows:
        names.setdefault(float(b["r"]), set()).add(b["attractor"])
    groups = {}
    for b in basin_rows:
        if len(names[float(b["r"])]) > 1:
            groups.setdefault((float(b["r"]), b["attractor"]), []).append(b)
    if not groups:
        return
    conv, extra = [], []
    for (r, name), g in sorted(groups.items()):
        g.sort(key=lambda b: -b["h"])
        for b in g:
            err = b["fraction"] - b["counted"]
            conv.append({"r": cell(r), "attractor": name, "boxes": b["boxes"], "h": cell(b["h"]),
                         "fraction": cell(b["fraction"], "{:.6f}"), "counted": cell(b["counted"], "{:.6f}"),
                         "ci_low": cell(b["ci_low"], "{:.6f}"), "ci_high": cell(b["ci_high"], "{:.6f}"),
                         "error": cell(err, "{:.6f}"),
                         "in_interval": "yes" if b["ci_low"] <= b["fraction"] <= b["ci_high"] else "no"})
        h = np.array([b["h"] for b in g])
        f = np.array([b["fraction"] for b in g])
        c, lo, hi = g[0]["counted"], g[0]["ci_low"], g[0]["ci_high"]
        e = np.abs(f - c)

        def slope(k):  # least-squares rate of |error| ~ h^p over the k finest resolutions
            if len(h) < k or k < 2 or np.any(e[-k:] <= 0):
                return float("nan")
            return float(np.polyfit(np.log(h[-k:]), np.log(e[-k:]), 1)[0])

        row = {"r": cell(r), "attractor": name, "resolutions": len(g), "finest": g[-1]["boxes"],
               "counted": cell(c, "{:.6f}"), "ci_low": cell(lo, "{:.6f}"), "ci_high": cell(hi, "{:.6f}"),
               "finest_fraction": cell(f[-1], "{:.6f}"), "finest_error": cell(f[-1] - c, "{:.6f}"),
               "rate_all": cell(slope(len(h))), "rate_3_finest": cell(slope(3))}
        q = E = E1 = est = A = float("nan")
        if len(f) >= 3:
            d1, d2 = f[-2] - f[-3], f[-1] - f[-2]
            q = math.log2(abs(d1 / d2)) if d1 != 0 and d2 != 0 else float("nan")
            E, E1 = 2 * f[-1] - f[-2], 2 * f[-2] - f[-3]
            est = abs(E - E1)
            # Aitken: the same extrapolation with the observed order q instead of 1 (meaningful when the three
            # differences shrink geometrically: d1 and d2 of one sign, |d2| < |d1|)
            if d1 * d2 > 0 and abs(d2) < abs(d1):
                A = f[-1] + d2 * d2 / (d1 - d2)
        row.update({"observed_order": cell(q), "richardson": cell(E, "{:.6f}"),
                    "richardson_coarser": cell(E1, "{:.6f}"), "richardson_error_estimate": cell(est, "{:.6f}"),
                    "richardson_error": cell(E - c, "{:.6f}"),
                    "richardson_in_interval": "" if not math.isfinite(E) else ("yes" if lo <= E <= hi else "no"),
                    "band_meets_interval": "" if not math.isfinite(E) else
                    ("yes" if E - est <= hi and E + est >= lo else "no"),
                    "aitken": cell(A, "{:.6f}"), "aitken_error": cell(A - c, "{:.6f}")})
        extra.append(row)
    write_csv(os.path.join(root, "basins_convergence.csv"), conv, list(conv[0].keys()))
    write_csv(os.path.join(root, "basins_extrapolation.csv"), extra, list(extra[0].keys()))
    print(f"wrote basins_convergence.csv ({len(conv)} rows) and basins_extrapolation.csv ({len(extra)} attractors)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rs = sorted({r for r, _ in groups})
    fig, axes = plt.subplots(1, len(rs), figsize=(6.5 * len(rs), 5.2), squeeze=False)
    for ax, r in zip(axes[0], rs):
        for k, ((rr, name), g) in enumerate(sorted((kv for kv in groups.items() if kv[0][0] == r))):
            h = np.array([b["h"] for b in g])
            e = np.array([abs(b["fraction"] - b["counted"]) for b in g])
            sign = np.array([b["fraction"] - b["counted"] for b in g])
            colour = plt.cm.tab10(k % 10)
            ms = max(4, 11 - 3 * k)  # coinciding curves (two attractors: errors +e and -e) stay visible
            ax.loglog(h, e, "-", color=colour, label=f"{name} (counted {g[0]['counted']:.4f})")
            ax.loglog(h[sign < 0], e[sign < 0], "o", color=colour, ms=ms)
            ax.loglog(h[sign >= 0], e[sign >= 0], "o", mfc="none", mec=colour, ms=ms, mew=1.5)
            ax.axhline((g[0]["ci_high"] - g[0]["ci_low"]) / 2, color=colour, ls=":", lw=1)
        hh = np.array(sorted({b["h"] for g in groups.values() for b in g if float(g[0]["r"]) == r}))
        ax.loglog(hh, 0.5 * hh / hh.max() * 0.2, "k--", lw=0.8, label="slope 1 (error ~ h)")
        ax.set_xlabel("box side h = 1/N (N x N boxes)")
        ax.set_ylabel("|Ulam basin fraction - counted fraction|")
        ax.set_title(f"r = {r:g}")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("Basins from the Ulam graph against the counted fractions of `btob basins` (Lebesgue, w1 in [-2, 2])"
                 "\nfilled: below the count, open: above; dotted: half-width of each counted 95% interval", fontsize=11)
    fig.tight_layout()
    save_atomic(fig, os.path.join(root, "basins_convergence.png"))
    print("wrote basins_convergence.png")


def gap_convergence(root):
    """The gap off the unit circle across r at every resolution of r_scan_*: gap_r.csv and gap_r.png."""
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scans = sorted(glob.glob(os.path.join(root, "r_scan_*", "spectrum_r.csv")),
                   key=lambda p: int(p.split("r_scan_")[1].split("/")[0]))
    if not scans:
        return
    cols, rs = {}, None
    for path in scans:
        b = path.split("r_scan_")[1].split("/")[0]
        s = np.genfromtxt(path, delimiter=",", names=True)
        rs = np.unique(s["r"])
        off = s["modulus"] < 1 - 1e-9
        cols[b] = [1 - s["modulus"][(s["r"] == r) & off].max() if np.any((s["r"] == r) & off) else float("nan") for r in rs]
    out = os.path.join(root, "gap_r.csv")
    with open(out + ".tmp", "w") as f:
        f.write("r," + ",".join(f"gap_{b}x{b}" for b in cols) + "\n")
        for i, r in enumerate(rs):
            f.write(f"{r:.10g}," + ",".join(f"{cols[b][i]:.6g}" for b in cols) + "\n")
    os.replace(out + ".tmp", out)
    fig, ax = plt.subplots(figsize=(11, 5))
    for b, g in cols.items():
        ax.plot(rs, g, ".-", ms=3, lw=0.8, label=f"{b} x {b} boxes")
    for x, name in ((7 - 4 * math.sqrt(3), "7-4sqrt3"), (3 - 2 * math.sqrt(2), "3-2sqrt2")):
        ax.axvline(x, color="k", ls="--", lw=1)
        ax.text(x, 1.0, " " + name, fontsize=8, va="top")
    ax.set_yscale("log")
    ax.set_xlabel("r")
    ax.set_ylabel("1 - |lambda|, leading eigenvalue off the unit circle")
    ax.set_title("Spectral gap of Ulam's operator of P_r across r at three resolutions (strip, 16 samples per box, "
                 "24 eigenvalues)\n(the roots of unity of the closed classes, |lambda| > 1 - 1e-9, excluded)")
    ax.legend()
    fig.tight_layout()
    save_atomic(fig, os.path.join(root, "gap_r.png"))
    print(f"wrote {out} and gap_r.png")


if __name__ == "__main__":
    main(sys.argv[1])
