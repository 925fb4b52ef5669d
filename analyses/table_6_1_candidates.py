#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Table 6.1 explained: which random initial data reproduce the paper's counts of periodic orbits out of ten.

Section 6.2 of the paper: at each r, "ten different orbits, all generated from initial data randomly chosen in the
strip", 5000 iterations, the last 2000 plotted; "when the orbits seemed to accumulate on only a finite number of
points, we considered that a periodic orbit was detected".  The paper does not say how it drew its points.  This
script draws n orbits per r from each of a family of candidate distributions (below), lets btob classify them
(btob.basins_r on the candidate's point list: the same orbits at every r) and asks how probable the paper's count is
under each (table_6_1_stats: beta-binomial, the fraction's own uncertainty integrated out), row by row and for the
whole table.  It then applies the paper's detection rule to the same orbits: their last 2000 of 5000 iterations
(btob.iterate, strip coordinates) are called periodic when, at the pixel size of the paper's plots, they show a finite
number of dots (table_6_1_stats.finite_at_resolution): model "<candidate>+rule".  For three candidates the rule is set
against btob's classifier orbit by orbit (btob.classify).

Usage: analyses/table_6_1_candidates.py [--orbits N] [--check-orbits M] [--seed S] [--threads T] [--out DIR]
Writes DIR (default results/attractors/table_6_1): candidates.csv, detection.csv, likelihood.csv,
table_6_1_candidates.png, detection.png and table_6_1_candidates.json (the manifest), each renamed into place.
Needs the Python module: PYTHONPATH=build/release/python (see results/attractors/README.md).
"""
import argparse
import csv
import io
import json
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "plot"))
import table_6_1_stats as st  # noqa: E402

PAPER_TABLE = os.path.join(HERE, "reference", "patterns_paper_table_6_1.csv")
PAPER_DRAWS = 10          # orbits per r in the paper
PAPER_ITERATIONS = 5000   # iterations per orbit in the paper
PAPER_TAIL = 2000         # last iterations plotted
# The paper's plots: -2 <= w1 <= 2, -1 <= w2 <= 1 (Section 6.2 on r = 0.2: a rescaled plot "with -30 <= w1 <= 30,
# instead of -2 <= w1 <= 2").  A MATLAB figure of
# the default 560 x 420 pixels has axes of 0.775 x 0.815 of it, 434 x 342 pixels: one pixel is 4/434 in w1 and
# 2/342 in w2.  Points whose pixels coincide are one point to the eye.
PIXEL_W1, PIXEL_W2 = 4 / 434, 2 / 342
# "A finite number of points": the tail splits into p <= MAX_PERIOD classes t mod p, each within BLOB_PIXELS pixels:
# p dots on the plot (table_6_1_stats.finite_at_resolution).  2 pixels is the size of MATLAB's '.' marker at that
# resolution.  MAX_PERIOD = 64: the longest period of Table 6.1 is 38 (132^36 at r = 0.172), and more than 64 dots
# evenly spread along an ellipse read as a dotted curve, not as points: where the P2 rotation number is within
# ~1e-6 of l/m with m <= 256 (21/68 at r = 0.32, 68/253 at r = 0.51) every P2 invariant curve shows m dots, and the
# paper, which lists no such pattern, did not count them.  Sensitivity (detection.csv): blobs of 0.5 and 8 pixels,
# periods up to 256, and the plain count of distinct pixels (at most 100), which also accepts small invariant curves.
BLOB_PIXELS = 2.0
# The blocks of Table 6.1 (its horizontal rules; 0.5-0.54 and 0.57-0.6 pooled, the range around 2^(2/3) - 1), each
# tested pooled: ten draws per row are too few for one row to reject a fraction of 0.35 when the paper saw 0.1.
BLOCKS = ((0.1, 0.103), (0.15, 0.17), (0.172, 0.18), (0.19, 0.25), (0.3, 0.34), (0.5, 0.6))
MAX_PERIOD = 64
FINITE_MAX_PIXELS = 100
SENSITIVITY = ((0.5, MAX_PERIOD), (8.0, MAX_PERIOD), (BLOB_PIXELS, 256))  # (blob pixels, longest period)


# ---- candidate initial distributions ------------------------------------------------------------------------------
# Each returns n directions u = (x, y, z) in the domain Q = {x >= 0, z <= 0} (any length: the map is projective).

def from_strip(w1, w2):
    """The point of the plane x - z = 1 with strip coordinates (w1, w2) (eq. (6.4) inverted)."""
    return np.column_stack([(1 + w2) / 2, w1, (w2 - 1) / 2])


def fold(u):
    """u or -u, whichever lies in Q (x >= 0); rows with x z > 0 are not in the domain and are rejected by callers."""
    return np.where(u[:, :1] < 0, -u, u)


def sample_strip(a):
    return lambda rng, n: from_strip(rng.uniform(-a, a, n), rng.uniform(-1, 1, n))


def sample_normal(sigma):
    return lambda rng, n: from_strip(rng.normal(0, sigma, n), rng.uniform(-1, 1, n))


def sample_sphere(rng, n):
    """Uniform on the sphere of directions restricted to Q: what MATLAB's X = randn(3,1) gives after Appendix A.2's
    X = -X when X(1) < 0, keeping X(1) X(3) < 0 (an isotropic law folded onto Q)."""
    out = np.empty((0, 3))
    while len(out) < n:
        u = fold(rng.normal(size=(2 * n, 3)))
        out = np.vstack([out, u[u[:, 2] < 0]])
    return out[:n]


def sample_angles(rng, n):
    """theta uniform in (0, pi/2), phi uniform in (0, pi): Appendix A.1's inputs theta0, phi0 drawn uniformly;
    u = (cos th sin ph, -cos ph, -sin th sin ph) (eq. (2.18), core::from_angles)."""
    th, ph = rng.uniform(0, np.pi / 2, n), rng.uniform(0, np.pi, n)
    return np.column_stack([np.cos(th) * np.sin(ph), -np.cos(ph), -np.sin(th) * np.sin(ph)])


def sample_cube(rng, n):
    """x ~ U(0, 1), y ~ U(-1, 1), z ~ U(-1, 0): Appendix A.2's input X (X(1) X(3) < 0) from MATLAB's rand, the
    signs of Section 4's grid X = (1, -., -.)."""
    return np.column_stack([rng.uniform(0, 1, n), rng.uniform(-1, 1, n), rng.uniform(-1, 0, n)])


def sample_particles(rng, n):
    """Random particles right after a b-collision (Section 2): gaps p1, p3 ~ U(0, 1) with particles 2, 3 in contact,
    velocities v1..v4 ~ U(-1, 1), kept when 2 and 3 separate (q2 = v3 - v2 > 0); u = p x q folded onto Q
    (core::from_particles)."""
    out = np.empty((0, 3))
    while len(out) < n:
        p = np.column_stack([rng.uniform(0, 1, 2 * n), np.zeros(2 * n), rng.uniform(0, 1, 2 * n)])
        q = np.diff(rng.uniform(-1, 1, (2 * n, 4)), axis=1)
        keep = q[:, 1] > 0
        out = np.vstack([out, fold(np.cross(p[keep], q[keep]))])
    return out[:n]


CANDIDATES = (
    [("sphere", "uniform on the sphere of directions (randn folded)", sample_sphere),
     ("angles", "theta, phi uniform (Appendix A.1 inputs)", sample_angles),
     ("cube", "x~U(0,1), y~U(-1,1), z~U(-1,0) (Appendix A.2 X)", sample_cube),
     ("particles", "random gaps and velocities after a b-collision", sample_particles)]
    + [(f"strip{a:g}", f"strip |w1| <= {a:g}, w2 ~ U(-1,1)", sample_strip(a)) for a in (0.1, 0.25, 0.5, 1, 2, 5, 30)]
    + [(f"normal{s:g}", f"w1 ~ N(0, {s:g}^2), w2 ~ U(-1,1)", sample_normal(s)) for s in (0.25, 0.5, 1, 2)])


def draw_points(index, n, seed):
    """Candidate `index`'s n points from its own stream (seed, index): adding a candidate changes no other's."""
    name, _, sample = CANDIDATES[index]
    u = sample(np.random.default_rng([seed, index]), n)
    u = u / np.linalg.norm(u, axis=1)[:, None]
    if not (np.all(np.isfinite(u)) and np.all(u[:, 0] >= 0) and np.all(u[:, 2] <= 0)):
        raise RuntimeError(f"candidate {name}: a point outside the domain x >= 0, z <= 0")
    return u


# ---- stages -------------------------------------------------------------------------------------------------------

def progress(stage, done, total):
    """A one-line bar on stderr when it is a terminal (nothing in logs)."""
    if not sys.stderr.isatty():
        return
    width = 30
    k = int(width * done / max(total, 1))
    sys.stderr.write(f"\r{stage:<28} [{'#' * k}{'.' * (width - k)}] {done}/{total}")
    sys.stderr.write("\n" if done >= total else "")
    sys.stderr.flush()


def read_paper_table(path=PAPER_TABLE):
    """Table 6.1: (r, periodic count out of ten) per row."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(float(row["r"]), round(float(row["percent_periodic_of_10_random_ics"]) * PAPER_DRAWS / 100))
            for row in rows]


def grid_spec(points):
    """btob's point-list grid: x,y,z;... with 17 significant digits (every double round-trips)."""
    return ";".join(f"{x:.17g},{y:.17g},{z:.17g}" for x, y, z in points)


PROVENANCE_KEYS = ("btob_version", "git_commit", "git_dirty", "run_dirty", "compiler", "build_type", "kernel_flags")


def periodic_counts(btob, points, r_values, threads, provenance=None):
    """btob's periodic orbits among `points` at each r (basins-r on the point list), as integers; `provenance`
    (a dict) receives the run's build and tree state (io::provenance: run_dirty covers analyses/)."""
    res = btob.basins_r(r_values=list(r_values), grid=grid_spec(points), threads=threads)
    a = res.attrs
    if provenance is not None:
        provenance.update({k: a[k] for k in PROVENANCE_KEYS})
    periodic = [j for j in range(int(a["columns"])) if a[f"column_{j}"].endswith("(periodic)")]
    order = {float(v): i for i, v in enumerate(res.r)}
    frac = np.asarray(res.fraction)
    counts = []
    for r in r_values:
        f = float(frac[order[float(r)], periodic].sum()) if periodic else 0.0
        counts.append(int(round(f * len(points))))  # fractions are counts / points: rounding recovers the count
    return counts


def beta_interval(k, n, level=0.95):
    """Central interval of the fraction's posterior Beta(k + 1, n - k + 1), by its CDF on a grid of 20001 points
    (interval ends within 5e-5 of the exact quantiles: far below the binomial spread of ten draws)."""
    f = np.linspace(0, 1, 20001)
    with np.errstate(divide="ignore", invalid="ignore"):  # 0 log 0 = 0 at the ends
        logd = np.where(f > 0, k * np.log(f), 0 if k == 0 else -np.inf) + \
            np.where(f < 1, (n - k) * np.log1p(-f), 0 if k == n else -np.inf)
    d = np.exp(logd - logd.max())
    cdf = np.cumsum(d) / d.sum()
    return float(f[np.searchsorted(cdf, (1 - level) / 2)]), float(f[np.searchsorted(cdf, (1 + level) / 2)])


def tails(btob, points, r, threads):
    """The last PAPER_TAIL of PAPER_ITERATIONS states of every orbit in strip coordinates (btob.iterate)."""
    kw = dict(record="tail", tail=PAPER_TAIL, threads=threads)
    return (btob.iterate(r, points, PAPER_ITERATIONS, coord="w1", **kw),
            btob.iterate(r, points, PAPER_ITERATIONS, coord="w2", **kw))


def verdicts(btob, points, r, threads):
    """btob's verdict (periodic, quasi-periodic, chaotic, collapse, undecided) on each orbit: btob.classify, one
    orbit per call on one thread each, `threads` calls at a time (the calls release the GIL)."""
    from concurrent.futures import ThreadPoolExecutor

    def one(u):
        return btob.classify(r=r, point=f"{u[0]:.17g},{u[1]:.17g},{u[2]:.17g}", threads=1).attrs["type"]

    with ThreadPoolExecutor(max_workers=threads) as pool:
        return list(pool.map(one, points))


def paper_rule(w1, w2, blob=BLOB_PIXELS, max_period=MAX_PERIOD):
    """The paper's criterion on each orbit's tail (table_6_1_stats.finite_at_resolution at the plot's pixels)."""
    return st.finite_at_resolution(w1, w2, PIXEL_W1, PIXEL_W2, blob, max_period)


def detection_rows(btob, name, points, r_values, threads):
    """Per r: btob's classifier against the paper's rule on the same orbits (counts of each combination), the
    pixel counts of each class, and the paper's rule at the other pixel sizes and thresholds."""
    rows, pixels_by_type = [], {}
    for i, r in enumerate(r_values):
        progress(f"detection ({name})", i, len(r_values))
        w1, w2 = tails(btob, points, r, threads)
        types = np.array(verdicts(btob, points, r, threads))
        finite = paper_rule(w1, w2)
        pixels = st.distinct_pixels(w1, w2, PIXEL_W1, PIXEL_W2)
        per = types == "periodic"
        for t in set(types):
            pixels_by_type.setdefault(t, []).extend(pixels[types == t].tolist())
        pixels_by_type.setdefault("rule_finite", []).extend(pixels[finite].tolist())
        row = {"candidate": name, "r": r, "orbits": len(points), "btob_periodic": int(per.sum()),
               "rule_periodic": int(finite.sum()), "both": int((per & finite).sum()),
               "btob_only": int((per & ~finite).sum()), "rule_only": int((~per & finite).sum()),
               "median_pixels_periodic": float(np.median(pixels[per])) if per.any() else "",
               "median_pixels_other": float(np.median(pixels[~per])) if (~per).any() else ""}
        for t in sorted(set(types) - {"periodic"}):
            row[f"rule_finite_among_{t}"] = int((finite & (types == t)).sum())
        for blob, max_period in SENSITIVITY:
            row[f"rule_periodic_blob{blob:g}px_p{max_period}"] = int(paper_rule(w1, w2, blob, max_period).sum())
        row[f"pixels_at_most_{FINITE_MAX_PIXELS}"] = int((pixels <= FINITE_MAX_PIXELS).sum())
        rows.append(row)
    progress(f"detection ({name})", len(r_values), len(r_values))
    return rows, pixels_by_type


def rule_counts(btob, points, r_values, threads):
    """Orbits among `points` that the paper's rule calls periodic at each r (tails from btob.iterate)."""
    return [int(paper_rule(*tails(btob, points, r, threads)).sum()) for r in r_values]


def histogram_rows(pixels_by_type):
    """Orbits per class of btob's classifier, and those the paper's rule calls finite, in log-spaced bins of distinct
    pixels [low, high)."""
    edges = np.unique(np.round(np.logspace(0, math.log10(PAPER_TAIL + 1), 36)).astype(int))
    types = ["periodic", "quasi-periodic", "chaotic", "collapse", "undecided", "rule_finite"]
    counts = {t: np.histogram(pixels_by_type.get(t, []), bins=edges)[0] for t in types}
    return [{"pixels_low": int(edges[i]), "pixels_high": int(edges[i + 1]), **{t: int(counts[t][i]) for t in types}}
            for i in range(len(edges) - 1)]


def candidate_rows(name, description, table, counts, n):
    """Per r: the paper's count against the candidate's btob count (table_6_1_stats.row_statistics)."""
    rows = []
    for (r, K), k in zip(table, counts):
        s = st.row_statistics(K, PAPER_DRAWS, k, n)
        lo, hi = beta_interval(k, n)
        rows.append({"candidate": name, "description": description, "r": r, "paper_count": K, "orbits": n,
                     "btob_periodic": k, "fraction": k / n, "fraction_low": lo, "fraction_high": hi,
                     "expected_count": s["expected"], "count_low": s["lo"], "count_high": s["hi"],
                     "prob_paper_count": s["prob"], "log_prob": s["log_prob"], "p_value": s["p_value"],
                     "inconsistent": "yes" if s["p_value"] < 0.01 else "no"})
    return rows


def likelihood_row(name, description, rows, rng, draws=20000):
    """One candidate's whole table: log-likelihood, its typical value under the candidate itself, the rows with
    p < 0.01, and the pooled fractions of r in [0.3, 0.34] and [0.5, 0.6] against the paper's."""
    quad = [(x["paper_count"], PAPER_DRAWS, x["btob_periodic"], x["orbits"]) for x in rows]
    mean, sd, share = st.table_goodness_of_fit(quad, draws, rng)

    def pooled(lo, hi):
        sel = [x for x in rows if lo <= x["r"] <= hi]
        return sum(x["btob_periodic"] for x in sel) / sum(x["orbits"] for x in sel)

    out = {"candidate": name, "description": description, "log_likelihood": sum(x["log_prob"] for x in rows),
           "expected_log_likelihood": mean, "sd_log_likelihood": sd, "gof_p": share,
           "inconsistent_rows": " ".join(f"{x['r']:g}" for x in rows if x["inconsistent"] == "yes"),
           "pooled_0.3_0.34": pooled(0.3, 0.34), "pooled_0.5_0.6": pooled(0.5, 0.6)}
    for lo, hi in BLOCKS:
        out[f"block_p_{lo:g}_{hi:g}"] = st.block_p_value([q for q, x in zip(quad, rows) if lo <= x["r"] <= hi])
    return out


# ---- output -------------------------------------------------------------------------------------------------------

def write_atomic(path, text):
    tmp = f"{path}.tmp-{os.getpid()}"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def csv_text(rows):
    """Rows as CSV that numpy.genfromtxt(names=True) reads as written: column names are identifiers ('-' becomes
    '_'), and the candidates' descriptions (free text with commas) are left to the manifest's "candidates"."""
    rows = [{k.replace("-", "_"): v for k, v in row.items() if k != "description"} for row in rows]
    keys = []
    for row in rows:
        keys += [k for k in row if k not in keys]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=keys, lineterminator="\n")
    w.writeheader()
    for row in rows:
        w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    return buf.getvalue()


def manifest(args, table, seconds, check_names, shown, provenance):
    """The result's manifest: btob's provenance (its build's commit and state, analyses/ clean or not at run time),
    the command, the seed and every size."""
    return {"name": "table_6_1_candidates", **provenance,
            "command": " ".join(["analyses/table_6_1_candidates.py"] + sys.argv[1:]),
            "seed": args.seed, "threads": args.threads, "orbits": args.orbits, "rule_orbits": args.rule_orbits,
            "check_orbits": args.check_orbits, "gof_draws": args.draws, "r_values": [r for r, _ in table],
            "paper_counts": [K for _, K in table], "paper_draws": PAPER_DRAWS, "iterations": PAPER_ITERATIONS,
            "tail": PAPER_TAIL, "transient": 5000, "classifier": "btob.basins_r / btob.classify, default thresholds",
            "pixel_w1": PIXEL_W1, "pixel_w2": PIXEL_W2, "blob_pixels": BLOB_PIXELS, "max_period": MAX_PERIOD,
            "finite_max_pixels": FINITE_MAX_PIXELS, "blocks": [list(b) for b in BLOCKS],
            "candidates": {name: desc for name, desc, _ in CANDIDATES}, "checked_candidates": check_names,
            "shown": shown, "total_seconds": seconds,
            "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--orbits", type=int, default=4000, help="orbits per r and candidate (btob's fraction), >= 10")
    p.add_argument("--rule-orbits", type=int, default=1000,
                   help="orbits per r and candidate classified by the paper's pixel rule, 10..orbits")
    p.add_argument("--check-orbits", type=int, default=100,
                   help="orbits per r of the orbit-by-orbit check of the rule against btob.classify, 1..orbits")
    p.add_argument("--seed", type=int, default=1, help="seed of every candidate's draw, >= 0")
    p.add_argument("--threads", type=int, default=2, help="threads of btob's runs, 1..1024")
    p.add_argument("--draws", type=int, default=20000, help="synthetic tables of the goodness of fit, >= 100")
    p.add_argument("--out", default=os.path.join(ROOT, "results", "attractors", "table_6_1"), help="output folder")
    args = p.parse_args(argv)
    for field, ok, want in (("orbits", args.orbits >= 10, ">= 10"),
                            ("rule-orbits", 10 <= args.rule_orbits <= args.orbits, f"10..{args.orbits} (orbits)"),
                            ("check-orbits", 1 <= args.check_orbits <= args.orbits, f"1..{args.orbits} (orbits)"),
                            ("seed", args.seed >= 0, ">= 0"), ("threads", 1 <= args.threads <= 1024, "1..1024"),
                            ("draws", args.draws >= 100, ">= 100")):
        if not ok:
            p.error(f"{field}: got {getattr(args, field.replace('-', '_'))}, expected {want}")
    return args


def candidate_stage(btob, args, table, rng):
    """Every candidate at every r: btob's classifier on args.orbits points, and the paper's rule on the first
    args.rule_orbits of them (model "<name>+rule")."""
    r_values = [r for r, _ in table]
    rows, like, points, provenance = [], [], {}, {}
    for i, (name, desc, _) in enumerate(CANDIDATES):
        progress("candidates", i, len(CANDIDATES))
        points[name] = draw_points(i, args.orbits, args.seed)
        for model, text, n, counts in (
                (name, desc, args.orbits, lambda: periodic_counts(btob, points[name], r_values, args.threads, provenance)),
                (f"{name}+rule", f"{desc}; the paper's pixel rule after {PAPER_ITERATIONS} iterations",
                 args.rule_orbits, lambda: rule_counts(btob, points[name][:args.rule_orbits], r_values, args.threads))):
            cand = candidate_rows(model, text, table, counts(), n)
            rows += cand
            like.append(likelihood_row(model, text, cand, rng, args.draws))
    progress("candidates", len(CANDIDATES), len(CANDIDATES))
    return rows, like, points, provenance


def detection_stage(btob, args, table, points, names):
    """The cross-check of the detection rule, orbit by orbit, for the candidates `names`."""
    det, pix = [], {}
    for name in names:
        d, p = detection_rows(btob, name, points[name][:args.check_orbits], [r for r, _ in table], args.threads)
        det += d
        for t, v in p.items():
            pix.setdefault(t, []).extend(v)
    for x in det:
        x["paper_count"] = dict(table)[x["r"]]
    return det, histogram_rows(pix)


def main(argv):
    args = parse_args(argv)
    import btob
    t0 = time.time()
    table = read_paper_table()
    rng = np.random.default_rng([args.seed, 10**6])  # the goodness-of-fit draws: a stream apart from the candidates'
    rows, like, points, provenance = candidate_stage(btob, args, table, rng)
    saturated = st.saturated_log_likelihood([K for _, K in table], PAPER_DRAWS)
    like.sort(key=lambda x: -x["log_likelihood"])
    for x in like:
        x["delta_to_best"] = x["log_likelihood"] - like[0]["log_likelihood"]
        x["saturated_log_likelihood"] = saturated
    best = next(x["candidate"] for x in like if not x["candidate"].endswith("+rule"))
    best_rule = next(x["candidate"] for x in like if x["candidate"].endswith("+rule"))
    check_names = list(dict.fromkeys(["sphere", best, best_rule[:-len("+rule")]]))
    det, hist = detection_stage(btob, args, table, points, check_names)
    shown = list(dict.fromkeys([best, best_rule, "sphere", "strip2"]))
    os.makedirs(args.out, exist_ok=True)
    files = {"candidates.csv": csv_text(rows), "likelihood.csv": csv_text(like), "detection.csv": csv_text(det),
             "detection_histogram.csv": csv_text(hist),
             "table_6_1_candidates.json": json.dumps(manifest(args, table, time.time() - t0, check_names, shown, provenance),
                                                     indent=1) + "\n"}
    for fname, text in files.items():
        write_atomic(os.path.join(args.out, fname), text)
    import matplotlib
    matplotlib.use("Agg")
    import attractors_table_6_1 as plot  # analyses/plot/: draws from the files just written
    plot.main(args.out)
    print(f"table_6_1_candidates: best {like[0]['candidate']} (log-likelihood {like[0]['log_likelihood']:.2f}, "
          f"saturated {saturated:.2f}); {len(CANDIDATES)} candidates x {len(table)} r x {args.orbits} orbits in "
          f"{time.time() - t0:.0f} s; wrote {args.out}")


if __name__ == "__main__":
    main(sys.argv[1:])
