#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes results/README.md: every figure of results/ at a glance, with what it shows, the paper's caption beside
it where it reproduces one, the command that made it and its compute time (read from the result's manifest).
Usage: analyses/gallery.py [REPO_ROOT]   (run by analyses/run_all.sh after everything else)"""
import json
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
P = "P̂_r"  # the b-to-b map
TAILS = f"Plot of the tails (last 100 iterations) of the orbits of {P}"

# (png, manifest, title, paper caption or None, what the image shows)
PAPER = [
    ("fig4_1/fig4_1.png", "fig4_1/fig4_1.json", "Figure 4.1",
     f"{TAILS.replace('the orbits', 'the 32 orbits')} for 0.0717 ≤ r ≤ 0.1717 after 5000 iterations, obtained with "
     "the algorithm of Appendix A.2.",
     "theta of the 32 orbits of the Section 4 grid, density per r; the windows of (ab)^n(cb)^n are the dark "
     "columns, chaos between them, the sink ababcbcb (1133) from 0.1275 to 3-2√2."),
    ("fig4_2/fig4_2.png", "fig4_2/fig4_2.json", "Figure 4.2",
     f"{TAILS.replace('the orbits', 'the 32 orbits')} for 0.0717 ≤ r ≤ 0.1717 after 5000 iterations, in logarithmic "
     "scale.",
     "the same in log10 theta with the window bounds (lower bound blue, r_crit,2(n) red); range chosen from the "
     "data, points outside counted in the figure, overlay lines closer than 5 px to a drawn one thinned (the plot script's MIN_GAP_PX)."),
    ("fig4_3/fig4_3.png", "fig4_3/fig4_3.json", "Figure 4.3",
     f"Plot of the tails of the orbits of {P} for 0.0717 ≤ r ≤ 0.0817 after 5000 iterations, in logarithmic scale.",
     "zoom towards 7-4√3: the windows n = 5 .. 100+ (Table B.1), each opening at its blue lower bound and closing at its red r_crit,2(n); theta collapses between them."),
    ("fig4_4/fig4_4.png", "fig4_4/fig4_4.json", "Figure 4.4",
     f"Plot of the tails of the orbits of {P} for 0.0717 ≤ r ≤ 0.0727 after 5000 iterations, in logarithmic scale.",
     "closer zoom: windows n = 15 .. 125; below 7-4√3 every orbit collapses (theta = 0, counted below the range)."),
    ("fig4_5/fig4_5.png", "fig4_5/fig4_5.json", "Figure 4.5",
     f"Plot of the tails of the orbits of {P} for 0.07179 ≤ r ≤ 0.07189 after 5000 iterations, in logarithmic scale.",
     "windows n = 47 .. 125 one after the other, theta down to 1e-220; the window bounds are ticks above the data "
     "(lower blue, r_crit,2 red), so that the narrow windows n >= 75 on the left stay visible."),
    ("fig4_6/fig4_6.png", "fig4_6/fig4_6.json", "Figure 4.6",
     f"Plot of the tails of the orbits of {P} for 0.07183 ≤ r ≤ 0.07184 after 5000 iterations, in logarithmic scale.",
     "the ten windows n = 69 .. 78 side by side."),
    ("fig4_7/fig4_7.png", "fig4_7/fig4_7.json", "Figure 4.7",
     f"Plot of the tails of the orbits of {P} for 0.0717 ≤ r ≤ 0.1717 after 5000 iterations, relying on the "
     "trigonometric algorithm of Section A.1.",
     "(a) btob's emulation of the paper's MATLAB code (MATLAB's acos: real on [-1, 1], complex outside), up to "
     "theta = pi/2 as the paper draws it; green squares on pi/2 where orbits froze there, red dots below theta = 0 "
     "where some orbit stopped producing b-collisions (the paper's red dots); (b) only the orbits that never left "
     "acos's domain; (c) per r, the orbits that left it and the tail states never reached. Below r = 0.078 the "
     "printed code draws no apparent chaos: orbits reach phi = pi/2 exactly and stop, or stay at theta = pi/2. GNU "
     "Octave running the printed code agrees (no complex acos on the grid at r = 0.072-0.078, 15-20 of 32 orbits "
     "stopped; analyses/octave/README.md), so the paper's panel was not drawn by the code as printed, run in IEEE "
     "double."),
    ("fig6_1a/fig6_1a.png", "fig6_1a/fig6_1a.json", "Figure 6.1a",
     f"{TAILS} for 0.1 ≤ r ≤ 0.102. (a) p-th iterations of {P} for 4900 ≤ p ≤ 5000.",
     "phi; six accumulation values of (ab)^3(cb)^3 below 5-2√6 (red), apparent chaos above."),
    ("fig6_1b/fig6_1b.png", "fig6_1b/fig6_1b.json", "Figure 6.1b",
     f"(b) p-th iterations of {P} for 24900 ≤ p ≤ 25000.",
     "the same after 25000 iterations: more r values have converged to the six values."),
    ("fig6_2/fig6_2.png", "fig6_2/fig6_2.json", "Figure 6.2",
     f"{TAILS.replace('the orbits', 'the 32 orbits')} for 0.16 ≤ r ≤ 0.56 after 5000 iterations.",
     "phi over the P2 rotation regime: quasi-periodic bands, thin stripes (r ≈ 0.27, 0.405), and the curved "
     "lines of periodic orbits outside the band."),
    ("fig6_3/fig6_3.png", "fig6_3/fig6_3.json", "Figure 6.3",
     f"{TAILS} for 0.191 ≤ r ≤ 0.195 after 5000 iterations.", "zoom: thin stripes at several scales."),
    ("fig6_4/fig6_4.png", "fig6_4/fig6_4.json", "Figure 6.4",
     f"{TAILS} for 0.5 ≤ r ≤ 0.6 after 5000 iterations.", "phi with 2^(2/3)-1 (red)."),
    ("fig6_5/fig6_5.png", "fig6_5/fig6_5.json", "Figure 6.5",
     f"{TAILS} for 0.1916 ≤ r ≤ 0.1917 after 5000 iterations.", "a narrow zoom inside Figure 6.3."),
    ("fig6_6/fig6_6.png", "fig6_6/fig6_6.json", "Figure 6.6",
     f"{TAILS} for 0.19 ≤ r ≤ 0.21 after 5000 iterations.",
     "ONE orbit from X = (1, 0.8, -1), inside the P2 rotation region (the paper does not print its start point): "
     "entangled curves and thin stripes, as the paper describes."),
    ("fig6_7/fig6_7.png", "fig6_7/fig6_7.json", "Figure 6.7",
     f"{TAILS} for 0.171 ≤ r ≤ 0.175 after 5000 iterations.",
     "just above 3-2√2 (red): accumulation points on a grid that refines as r → 3-2√2."),
    ("fig6_8/fig6_8.png", "fig6_8/fig6_8.json", "Figure 6.8",
     f"{TAILS} for 0.191 ≤ r ≤ 0.195 after 5000 iterations, together with the restitution coefficients of the form "
     "(6.3), with 1 ≤ m ≤ 120.",
     "Figure 6.3 with the thin-stripe values r(l/m) of eq. (6.3) (blue): they sit on the stripes."),
    ("fig6_9/fig6_9.png", "fig6_9/fig6_9.json", "Figure 6.9",
     f"Plot of the tails (last 2000 iterations) of the orbits of {P} after 5000 iterations, for r = 0.2. "
     "(Panels: 1st, 3rd, 6th, 10th simulations quasi-periodic; 2nd, 4th, 5th, 7th, 8th, 9th periodic.)",
     "ten orbits from seeded random points of the strip, each panel titled by btob's classifier: 9 periodic "
     "(132^3312^3, 8 of its 10 points inside |w1| ≤ 2, as the paper counts) and 1 quasi-periodic (the paper: 6 and 4)."),
    ("fig6_10/fig6_10.png", "fig6_10/fig6_10.json", "Figure 6.10",
     "Rescaled plot of the orbit represented on Figure 6.9 (second simulation).",
     "the second orbit with -30 ≤ w1 ≤ 30: the two far points per period of 132^3312^3 (w1 ≈ ±26)."),
    ("fig6_11/fig6_11.png", "fig6_11/fig6_11.json", "Figure 6.11",
     f"Plot of the tails (last 2000 iterations) of the orbits of {P} after 5000 iterations, for r = 0.1717.",
     "one orbit at r = 0.1717; the classifier finds 132^67312^67 (period 138), the pattern the paper reads off "
     "the trajectory, for all ten random starts."),
    ("fig7_132312/fig7_1.png", "fig7_132312/fig7_132312.json", "Figure 7.1",
     "Eigenvalues of the collision matrix P̃_{132^J}, as functions of the restitution coefficient r, in the case when "
     "these eigenvalues are real. (a) Spectrum (when real) for 0 ≤ r ≤ 1. (b) Magnification of the plot of the "
     "spectrum (when real), for 0 ≤ r ≤ 0.19.",
     "the real eigenvalues of J P2 P3 P1: three below r_Δ = 3-2√2, one above; all negative."),
    ("fig7_132312/fig7_2.png", "fig7_132312/fig7_132312.json", "Figure 7.2",
     "Moduli of the eigenvalues of the collision matrix P̃_{132^J}, as functions of the restitution coefficient r. "
     "(a) Moduli of the eigenvalues for 0 ≤ r ≤ 1. (b) Magnification of the plot of the moduli of the eigenvalues, "
     "for 0 ≤ r ≤ 0.3.",
     "moduli on a log scale: the eigenvalue real for every r dominates everywhere (Theorem 7.1)."),
    ("fig7_132312/fig7_3.png", "fig7_132312/fig7_132312.json", "Figure 7.3",
     "The two first feasibility inequalities associated to the pattern 132312. (a) First feasibility "
     "inequality for 132312: plot of (u_{λ^dom})_z as a function of r. (b) Second feasibility inequality for 132312: "
     "plot of α (u_{λ^dom})_y - (u_{λ^dom})_x as a function of r.",
     "(u)_z and alpha (u)_y - (u)_x of the dominant eigenvector (u_x = 1, symlog): the pole at r_crit,132J,1 = "
     "0.182615 (red), and the sign change of the second at 0.2201 = r_crit,132J (Theorem 7.1)."),
    ("fig7_132312/fig7_4.png", "fig7_132312/fig7_132312.json", "Figure 7.4",
     "Third and fourth feasibility inequalities associated to the pattern 132312. (a) Third feasibility inequality "
     "for 132312: plot of (P_1 u_{λ^dom})_y as a function of r. (b) Fourth feasibility inequality for 132312: plot of "
     "α (P_1 u_{λ^dom})_y - (P_1 u_{λ^dom})_z as a function of r.",
     "(P1 u)_y and alpha (P1 u)_y - (P1 u)_z: both negative for r > r_crit,132J,1."),
    ("fig7_132312/fig7_5.png", "fig7_132312/fig7_132312.json", "Figure 7.5",
     "The two last feasibility inequalities associated to the pattern 132312. (a) Fifth feasibility inequality for "
     "132312: plot of α (P_3 P_1 u_{λ^dom})_y - (P_3 P_1 u_{λ^dom})_x as a function of r. (b) Sixth feasibility inequality "
     "for 132312: plot of α (P_3 P_1 u_{λ^dom})_y - (P_3 P_1 u_{λ^dom})_z as a function of r.",
     "alpha (P3P1u)_y - (P3P1u)_x < 0 and alpha (P3P1u)_y - (P3P1u)_z > 0 for r > r_crit,132J,1."),
    ("fig7_13223122/fig7_6.png", "fig7_13223122/fig7_13223122.json", "Figure 7.6",
     "Eigenvalues of the collision matrix P̃_{1322^J}, as functions of the restitution coefficient r, in the case "
     "when these eigenvalues are real. (a) Spectrum (when real) for 0 ≤ r ≤ 1. (b) Magnification of the plot of "
     "the spectrum (when real), for 0 ≤ r ≤ 0.3.",
     "the real eigenvalues of J P2 P2 P3 P1, with r_crit,1322J,1 and 2 (dashed) where the negative one starts and "
     "stops dominating."),
    ("fig7_13223122/fig7_7.png", "fig7_13223122/fig7_13223122.json", "Figure 7.7",
     "Moduli of the eigenvalues of the collision matrix P̃_{1322^J}, as functions of the restitution coefficient r. "
     "(a) Moduli of the eigenvalues for 0 ≤ r ≤ 1. (b) Magnification of the plot of the moduli of the eigenvalues, "
     "for 0 ≤ r ≤ 0.3.",
     "moduli (log): the negative real eigenvalue dominates only between 0.160290 and 0.251127."),
    ("fig7_13223122/fig7_8.png", "fig7_13223122/fig7_13223122.json", "Figure 7.8",
     "The two first feasibility inequalities associated to the pattern 13223122. (a) First feasibility inequality "
     "for 13223122: plot of (u_{λ^dom})_z as a function of r. (b) Second feasibility inequality for 13223122: plot of "
     "α (u_{λ^dom})_y - (u_{λ^dom})_x as a function of r.",
     "(u)_z and alpha (u)_y - (u)_x of the eigenvector of lambda^real (u_x = 1): both vanish at 3-2√2 = 0.171573 "
     "with opposite requirements, so 13223122 is never stable (Theorem 7.3); r_crit,1322J,3 = 0.236362 solid red."),
]
LAB = [
    ("float_vs_double/float_vs_double.png", "float_vs_double/fig4_1_float.json", "Figure 4.1 in float and double",
     "the Figure 4.1 workload in log10 theta in both precisions and their binned KS distance per r."),
    ("windows/precision.png", "windows/precision.json", "Window bounds: digits against n",
     "how many digits each precision gets of the window bounds of (ab)^n(cb)^n (Table B.1)."),
    ("patterns/atlas.png", "patterns/atlas.json", "Atlas of stable periodic patterns",
     "stability windows (analysis) of every stable word up to 12 symbols, with the iterator's detections at the "
     "Table 6.1 r values."),
    ("attractors/basins_r/fractions_r.png", "attractors/basins_r/fractions_r.json", "Basin fractions across r",
     "share of 2000 random initial conditions (uniform on the sphere of directions) reaching each attractor at the "
     "Table 6.1 r values."),
    ("attractors/table_6_1/table_6_1_candidates.png", "attractors/table_6_1/table_6_1_candidates.json",
     "Table 6.1 against candidate initial distributions",
     "the paper's periodic counts out of ten against each candidate distribution's expected count (btob's fraction, "
     "beta-binomial 95% interval), the rows' p-values, and the table's log-likelihood per candidate "
     "(attractors/README.md)."),
    ("attractors/table_6_1/detection.png", "attractors/table_6_1/table_6_1_candidates.json",
     "Table 6.1: the paper's detection rule against btob's classifier",
     "the same orbits classified by btob and by the paper's rule (a finite number of dots among the last 2000 of "
     "5000 iterations at the pixel size of its plots)."),
] + [(f"attractors/basins_sphere_r{r}/basins.png", f"attractors/basins_sphere_r{r}/basins.json", f"Basins at r = {r}",
      "basin map on the equal-area grid (theta, y): fractions of the uniform measure on the sphere of directions.")
     for r in ("0.05", "0.1", "0.15", "0.172", "0.2", "0.21", "0.24", "0.3", "0.58")] + [
    (f"attractors/basins_r{r}/basins.png", f"attractors/basins_r{r}/basins.json",
     f"Basins at r = {r.replace('_wide', ' (wide strip)')}, strip rectangle",
     "basin map on a strip grid: fractions of Lebesgue measure on the rectangle (its share of the sphere measure in "
     "the title).")
    for r in ("0.05", "0.1", "0.15", "0.172", "0.2", "0.2_wide", "0.21", "0.24", "0.3", "0.58")] + [
    (f"leaves/leaves_r{r}.png", f"leaves/leaves_r{r}.json", f"P2's invariant curves (leaves), r = {r}",
     "where the orbits of a 100 x 100 sphere grid land (the label t of their leaf), the landing law against the "
     "region's own, the rotation number per leaf against theta / (2 pi), and the measure on a leaf: the uniform "
     "eigen-angle holds, normalised arc length is rejected (Kolmogorov-Smirnov).")
    for r in ("0.2", "0.25", "0.3")] + [
    ("leaves/leaves_sweep.png", "leaves/leaves_sweep.json", "P2's invariant curves across r",
     "theta / (2 pi) with the resonances l / m, the region's measure against the landing mass, the landing law's "
     "moments and its density, for 0.18 <= r <= 0.9."),
    ("lyapunov/lyapunov_map.png", "lyapunov/lyapunov_map.json", "Lyapunov map",
     "largest Lyapunov exponent of the 32 paper-grid orbits against r, and the share of positive/zero/negative."),
    ("lyapunov/lyapunov_strip_r0.3.png", "lyapunov/lyapunov_strip_r0.3.json", "Lyapunov exponents over the strip, r = 0.3",
     "lambda1 of orbits started on a strip grid."),
    ("hyperbolicity/hyperbolicity_orbits.png", "hyperbolicity/hyperbolicity_orbits.json", "Non-hyperbolicity along orbits",
     "fraction of expanding steps and the angle between covariant Lyapunov vectors against r."),
    ("hyperbolicity/hyperbolicity_strip_r0.11.png", "hyperbolicity/hyperbolicity_strip_r0.11.json",
     "One-step singular values over the strip, r = 0.11", "where the map expands, on the strip."),
    ("hyperbolicity/hyperbolicity_strip_r0.3.png", "hyperbolicity/hyperbolicity_strip_r0.3.json",
     "One-step singular values over the strip, r = 0.3", "where the map expands, on the strip."),
    ("stats/measure_r0.15.png", "stats/measure_r0.15.json", "Empirical measures, r = 0.15",
     "the 32 orbits all carry the same measure: four atoms of mass 1/4 (the sink 1133)."),
    ("stats/measure_r0.15_transient0.png", "stats/measure_r0.15_transient0.json", "Empirical measures, r = 0.15, no transient",
     "convergence of the empirical measures against N without a transient."),
    ("stats/measure_r0.2_curves.png", "stats/measure_r0.2_curves.json", "Empirical measures on invariant curves, r = 0.2",
     "orbits on different invariant curves of the P2 rotation carry different measures."),
    ("stats/measure_r0.2_curves_angles.png", "stats/measure_r0.2_curves_angles.json",
     "The same in the angles (theta, phi)", "the measures of r = 0.2 in angle coordinates."),
    ("stats/correlation_periodic_r0.15.png", "stats/correlation_periodic_r0.15.json", "C_N on the sink 1133, r = 0.15",
     "correlations of phi: period 4, no decay."),
    ("stats/correlation_quasiperiodic_r0.2.png", "stats/correlation_quasiperiodic_r0.2.json",
     "C_N on an invariant curve, r = 0.2", "correlations of phi: quasi-periodic, no decay."),
    ("stats/correlation_chaotic_r0.11.png", "stats/correlation_chaotic_r0.11.json", "C_N at the chaotic r = 0.11",
     "correlations of phi: decay to the noise floor."),
    ("precision/tradeoff.png", "precision/tradeoff.json", "Speed against accuracy",
     "per precision and algorithm: symbol agreement with a 256-digit run, state error, Lyapunov error, and window "
     "widths against the spacing of representable r."),
    ("benchmarks/bm_iterate.png", None, "Iterator throughput", "map iterations per second of the batched kernel against "
     "the scalar loop of Appendix A.2."),
]



def read_csv(path):
    import csv
    full = os.path.join(ROOT, path)
    return list(csv.DictReader(open(full))) if os.path.exists(full) else []


def candidate_names():
    """The candidate distributions' descriptions, from the analysis's manifest ({name: description})."""
    m = manifest("attractors/table_6_1/table_6_1_candidates.json")
    return m.get("candidates", {})


def p_text(gof_p):
    """A goodness-of-fit p-value from 20000 synthetic tables (table_6_1_candidates.py): 0 means below 1/20000."""
    return f"p = {float(gof_p):.2f}" if float(gof_p) > 0 else "p < 5e-5"


def table_6_1_conclusion(lik):
    """The candidate analysis's conclusion, from likelihood.csv (rows sorted best first): the best candidate, its fit,
    and the sphere measure under which basins-r counts."""
    desc = candidate_names()
    best = lik[0]
    name = best["candidate"]
    base = name.replace("+rule", "")
    sphere = next((r for r in lik if r["candidate"] == "sphere"), None)
    text = (f"**Which start points reproduce the paper's counts** (`analyses/table_6_1_candidates.py`, "
            f"`results/attractors/table_6_1/`): of {len(lik) // 2} candidate start distributions, each judged by btob's "
            f"classifier and by the paper's detection rule, the best is {desc.get(base, base)}"
            f"{' under the paper' + chr(39) + 's rule' if name.endswith('+rule') else ' under btob' + chr(39) + 's classifier'}, "
            f"log-likelihood {float(best['log_likelihood']):.1f} against a typical "
            f"{float(best['expected_log_likelihood']):.1f} +- {float(best['sd_log_likelihood']):.1f} "
            f"(goodness of fit {p_text(best['gof_p'])}).")
    if sphere:
        text += (f" The uniform measure on the sphere of directions, under which `btob basins-r` counts, is rejected "
                 f"(log-likelihood {float(sphere['log_likelihood']):.1f}, {p_text(sphere['gof_p'])}).")
    return text + (" The table gives per r the paper's row, the best candidate's expected count of periodic orbits "
                   "out of ten with its 95% predictive interval and the row's two-sided p-value, and the patterns "
                   "btob finds at that r (2000 orbits uniform on the sphere: the patterns, not their shares).")


def table_6_1():
    """Table 6.1 as the paper prints it (periodic %, patterns, their lengths), led by the candidate analysis's
    conclusion, each row scored under the best-fitting start distribution, and the patterns btob finds."""
    paper = read_csv("analyses/reference/patterns_paper_table_6_1.csv")
    lik = sorted(read_csv("results/attractors/table_6_1/likelihood.csv"), key=lambda r: -float(r["log_likelihood"]))
    if not paper or not lik:
        return []
    best = lik[0]["candidate"]
    scored = {r["r"]: r for r in read_csv("results/attractors/table_6_1/candidates.csv") if r["candidate"] == best}
    found = {r["r"]: r for r in read_csv("results/attractors/basins_r/table_6_1_comparison.csv")}
    out = ["### Table 6.1", "", table_6_1_conclusion(lik), "",
           f"| r | paper: periodic % | paper's patterns | paper: length | {best}: expected of 10 [95%] | row p | "
           "btob's patterns (share of the sphere measure) |", "|---|---|---|---|---|---|---|"]
    for p in paper:
        c, f = scored.get(p["r"], {}), found.get(p["r"], {})
        p = {k: v.replace(";", ", ") for k, v in p.items()}
        expected = f"{float(c['expected_count']):.1f} [{c['count_low']}, {c['count_high']}]" if c else ""
        out.append(f"| {p['r']} | {p['percent_periodic_of_10_random_ics']} | {p['patterns_detected'] or 'none'} | "
                   f"{p['pattern_lengths_in_collisions'] or '--'} | {expected} | "
                   f"{float(c['p_value']):.2g} | {f.get('patterns_found', '')} |" if c else
                   f"| {p['r']} | {p['percent_periodic_of_10_random_ics']} | {p['patterns_detected'] or 'none'} | "
                   f"{p['pattern_lengths_in_collisions'] or '--'} | | | {f.get('patterns_found', '')} |")
    return out + [""]


def tables():
    """Tables 6.1, B.1 and B.2 beside the paper's, from the committed results and the transcribed tables."""
    out = ["## The paper's tables", ""]
    out += table_6_1()
    paper = {r["n"]: r for r in read_csv("analyses/reference/windows_paper_table_B1.csv")}
    ours = {r["n"]: r for r in read_csv("results/windows/bounds_certified.csv")}
    if paper and ours:
        out += ["### Table B.1", "",
                "Lower bounds of the windows of (ab)^n(cb)^n (smallest positive root of Q_n, eq. (4.3)) and "
                "r_crit,2(n) (eq. (4.6)), 12 decimals; btob's lower bounds are certified in exact rational "
                "arithmetic (`analyses/windows.sh`, `results/windows/bounds_certified.csv`). A differing value is "
                "**bold**.", "", "| n | paper: lower | btob: lower | paper: r_crit,2 | btob: r_crit,2 | certified |",
                "|---|---|---|---|---|---|"]
        for n in sorted(paper, key=int):
            p, o = paper[n], ours.get(n, {})
            cell = lambda a, b: f"**{b}**" if a and b and a != b else (b or "")  # noqa: E731
            out.append(f"| {n} | {p['lower_bound']} | {cell(p['lower_bound'], o.get('lower_bound', ''))} | "
                       f"{p['upper_bound']} | {cell(p['upper_bound'], o.get('upper_bound', ''))} | "
                       f"{o.get('certified', '')} |")
        out.append("")
    b2 = os.path.join(ROOT, "results", "windows", "table_B2.txt")
    if os.path.exists(b2):
        out += ["### Table B.2", "", "The polynomials Q_n, n = 1..10, exact (`btob windows poly --n 1..10`, "
                "`results/windows/table_B2.txt`). The paper prints +81/128 r^4 in Q_2; the coefficient is -81/128.",
                "", "```text", open(b2).read().rstrip(), "```", ""]
    return out


def transfer_and_particles():
    """The transfer operator's figures (one per r and resolution, the r scans, the basins' convergence and the gap)
    and the particles' (a space-time diagram per simulated pattern, the feasible atlas), found on disk so that a new
    run of analyses/transfer.sh or analyses/particles.sh appears without an edit here."""
    import glob
    res = os.path.join(ROOT, "results")
    rel = lambda p: os.path.relpath(p, res)  # noqa: E731
    key = lambda p: [float(x) if x.replace(".", "").isdigit() else x for x in  # noqa: E731
                     os.path.basename(os.path.dirname(p)).replace("r_scan_", "scan_").lstrip("r").split("_")]
    out = []
    for png in sorted(glob.glob(os.path.join(res, "transfer", "r*_*", "transfer.png")), key=key):
        r, n = os.path.basename(os.path.dirname(png)).lstrip("r").split("_")
        out.append((rel(png), rel(png)[:-4] + ".json", f"Transfer operator, r = {r}, {n} x {n} boxes",
                    "Ulam's matrix on the strip chart (atan w1, w2): the invariant density, the leading eigenvalues, "
                    "the ergodic classes and, on the right, the basins from the Ulam graph (absorption probabilities)."))
    for png in sorted(glob.glob(os.path.join(res, "transfer", "r_scan_*", "transfer_r.png")), key=key):
        n = os.path.basename(os.path.dirname(png)).split("_")[-1]
        out.append((rel(png), rel(png)[:-4] + ".json", f"Transfer operator across r, {n} x {n} boxes",
                    "peripheral eigenvalues and the gap 1 - |lambda| against r."))
    out += [("transfer/basins_convergence.png", None, "Transfer operator: basins against the resolution",
             "basin fractions from the Ulam graph against the counted ones of btob basins, per resolution."),
            ("transfer/gap_r.png", None, "Transfer operator: the spectral gap across r",
             "the gap at three resolutions: it stays open below 3 - 2√2 and closes with the resolution above.")]
    for png in sorted(glob.glob(os.path.join(res, "particles", "*_r*", "spacetime.png"))):
        word, r = os.path.basename(os.path.dirname(png)).split("_r")
        out.append((rel(png), os.path.join(os.path.dirname(rel(png)), "particles.json"),
                    f"Four particles on the pattern {word}, r = {r}",
                    "space-time diagram of the four particles started on the periodic point (rescaled every period)."))
    out.append(("particles/atlas/feasible.png", "particles/atlas/feasible.json", "Feasible periodic patterns",
                "which words of length ≤ 14 have a feasible periodic point, stable or not, against r."))
    return out


TIME_KEYS = ("total_seconds", "seconds", "atlas_seconds", "clv_seconds", "iteration_seconds")


def manifest(path):
    if not path or not os.path.exists(os.path.join(ROOT, "results", path)):
        return {}
    with open(os.path.join(ROOT, "results", path)) as f:
        return json.load(f)


def command(m):
    c = m.get("command", "")
    if " -> " in c:
        c = c.split(" -> ")[0]
    return re.sub(r"^\S*/btob\S*(?=\s)", "btob", c.strip()) or "see README.md"  # any build's path to the binary


def seconds(m):
    for k in TIME_KEYS:
        if k in m:
            return f"{float(m[k]):.3g} s" + (" (iteration)" if k == "iteration_seconds" else "")
    return "not recorded"


def main():
    out = ["# Results at a glance", "",
           "Every figure `analyses/run_all.sh` writes, with what it shows, the paper's caption beside it where it "
           "reproduces one, the command that made it (run from the repository root, `btob` = `build/release/btob`) "
           "and its compute time from the result's manifest (plotting excluded, 2 cores). This page is written by "
           "`analyses/gallery.py`.", "", "## The paper's figures", ""]
    for png, man, title, caption, what in PAPER:
        m = manifest(man)
        out += [f"### {title}", "", f"<img src=\"{png}\" width=\"720\">", "",
                "| | |", "|---|---|", f"| paper's caption | {caption} |", f"| what the image shows | {what} |",
                f"| command | `{command(m)}` |", f"| compute time | {seconds(m)} |", ""]
    out += tables()
    out += ["## The lab's own figures", ""]
    for png, man, title, what in LAB + transfer_and_particles():
        if not os.path.exists(os.path.join(ROOT, "results", png)):
            continue
        m = manifest(man)
        out += [f"### {title}", "", f"<img src=\"{png}\" width=\"720\">", "", "| | |", "|---|---|",
                f"| what the image shows | {what} |", f"| command | `{command(m)}` |",
                f"| compute time | {seconds(m)} |", ""]
    tmp = os.path.join(ROOT, "results", f"README.md.tmp-{os.getpid()}")
    with open(tmp, "w") as f:
        f.write("\n".join(out))
    os.replace(tmp, os.path.join(ROOT, "results", "README.md"))


if __name__ == "__main__":
    main()
