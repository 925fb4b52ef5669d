"""Convergence table of results/transfer: every `btob transfer` run's key numbers, grouped by r, three resolutions
each (issue 20, item 3).  Usage: transfer_summary.py results/transfer  -> results/transfer/convergence.csv"""
import csv
import glob
import json
import math
import os
import sys


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
    rows = []
    for man in sorted(glob.glob(os.path.join(root, "r0.*_*", "transfer.json"))):
        d = os.path.dirname(man)
        a = json.load(open(man))
        spec = list(csv.DictReader(open(os.path.join(d, "spectrum.csv"))))
        comps = list(csv.DictReader(open(os.path.join(d, "components.csv"))))
        cyc_path = os.path.join(d, "cycles.csv")
        cycles = list(csv.DictReader(open(cyc_path))) if os.path.exists(cyc_path) else []
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
        rows.append({
            "r": a["r"], "boxes": a["boxes"], "samples": a["samples"], "nnz": a["nnz"],
            "matrix_MB": round(a["matrix_bytes"] / 1e6, 2), "seconds": round(a["seconds"], 2),
            "closed_classes": a["closed_classes"], "near_one_count": a["near_one_count"],
            "unit_circle_count": sum(1 for z in lam if abs(z) > 1 - 1e-9),
            "near_one_values": ";".join(f"{z.real:.6f}" for z in lam if abs(z.imag) < 1e-12 and abs(z - 1) <= 0.01),
            "above_0.99": sum(1 for z in lam if abs(z) > 0.99),
            "components": len(comps),
            "component_fractions": ";".join(f'{float(c["lebesgue_fraction"]):.4f}' for c in comps),
            "component_rho": ";".join(f'{float(c["rho"]):.6f}' for c in comps),
            "lambda_next_real": a["second_value"],
            "rotation_modulus": rot_mod, "rotation_arg_error": rot_arg_err,
            "cycle_radius99": ";".join(f'{c["word"]}:{c["radius99"]}' for c in cycles),
            "cycle_mass_3x3": ";".join(f'{c["word"]}:{float(c["mass_neighbourhood"]):.4f}' for c in cycles),
            "tv_boxes": a["tv_boxes"], "tv_32x32": a["tv_coarse"],
            # Basins from the Ulam graph against the counted fractions of `btob basins` (same Lebesgue rectangle);
            # an interval is written [lo hi], without a comma, so that the cell needs no quoting (tests/cli_csv.py)
            "basin_fractions": ";".join(f'{b["attractor"]}:{float(b["fraction"]):.4f}' for b in basins),
            "counted_fractions": ";".join(
                f'{b["attractor"]}:{counted[key(b)][0]:.4f}[{counted[key(b)][1]:.4f} {counted[key(b)][2]:.4f}]'
                for b in basins if key(b) in counted),
        })
    rows.sort(key=lambda x: (float(x["r"]), int(str(x["boxes"]).split("x")[0])))
    out = os.path.join(root, "convergence.csv")
    with open(out + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(out + ".tmp", out)
    print(f"wrote {out} ({len(rows)} runs)")
    gap_convergence(root)


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
    tmp = os.path.join(root, f"gap_r.png.tmp-{os.getpid()}.png")
    fig.savefig(tmp)
    os.replace(tmp, os.path.join(root, "gap_r.png"))
    print(f"wrote {out} and gap_r.png")


if __name__ == "__main__":
    main(sys.argv[1])
