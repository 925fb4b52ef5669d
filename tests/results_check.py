#!/usr/bin/env python3
"""Quick mode of the runner (DESIGN.md): re-runs the cheap commands behind committed files of results/ into a
temporary directory and compares the numbers with the committed ones, within the tolerances stated below.

Usage: results_check.py PATH/TO/btob REPO_ROOT
Exit 0 when every check passes, 1 otherwise (each failure printed with the file, row and both values).

Tolerances. Exact-arithmetic and high-precision outputs (window bounds) must match to the last printed digit.
Outputs that depend only on orbits converging to sinks (C_N on the sink 1133, window verification, pattern
windows by bisection to 1e-15) match to 1e-9 relative: they are reproducible across instruction sets up to
rounding.  Outputs that average over chaotic orbits (Lyapunov medians, basin fractions) are bit-identical on the
same build, but a build for another instruction set (SSE2 without FMA) follows chaotic orbits differently after
~50 steps, so they are compared statistically: basin fractions of 2000 orbits within 0.035 (3.2 binomial
standard deviations at p = 0.5), and the per-r median exponent within 0.02 for at least 98% of the 5000 r values.
"""
import csv
import io
import os
import re
import subprocess
import sys
import tempfile

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def run(btob, *args):
    p = subprocess.run([btob, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(f"btob {' '.join(args)} exited {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def rows(path_or_text, is_text=False):
    text = path_or_text if is_text else open(path_or_text).read()
    lines = [l for l in text.splitlines() if l and not l.startswith("#")]
    return list(csv.DictReader(io.StringIO("\n".join(lines))))


def close(a, b, rel):
    a, b = float(a), float(b)
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def rerun(btob, args, new_file, committed, what, unit):
    """Runs btob with args, reads new_file and the committed CSV (path under the repository root); reports a
    different row count.  Returns (new rows, committed rows)."""
    run(btob, *args)
    new, old = rows(new_file), rows(committed)
    if len(new) != len(old):
        fail(f"{what}: {len(new)} {unit}, committed {len(old)}")
    return new, old


def symbols(btob, word):
    """Length in symbols of a word in the paper's notation, as btob's own parser reads it (132^3312^3 = 10)."""
    first = run(btob, "pattern", word, "--r", "0.5").splitlines()[0]
    m = re.search(r"\((\d+) symbols", first)
    if not m:
        fail(f"btob pattern {word}: no symbol count in '{first}'")
        return 0
    return int(m.group(1))


def check_window_bounds(btob, root):
    # Table B.1 route: exact Q_n and MPFR roots, printed to 12 decimals -> identical text.
    new = rows(run(btob, "windows", "bounds", "--n", "1..100"), is_text=True)
    old = rows(os.path.join(root, "results/windows/bounds_certified.csv"))
    if len(new) != len(old):
        fail(f"windows bounds: {len(new)} rows, committed {len(old)}")
    for a, b in zip(new, old):
        for k in ("n", "lower_bound", "upper_bound"):
            if a[k] != b[k]:
                fail(f"windows bounds n={b['n']} {k}: {a[k]} != committed {b[k]}")
    print(f"ok: windows bounds n = 1..100 ({len(new)} rows)")


def check_window_verify(btob, root, tmp):
    out = os.path.join(tmp, "verify")
    run(btob, "windows", "verify", "--n", "2..20", "--out", out, "--quiet")
    new = rows(os.path.join(out, "verify_2-20.csv"))
    old = [r for r in rows(os.path.join(root, "results/windows/verify.csv")) if int(r["n"]) <= 20]  # a subset
    if len(new) != len(old):
        fail(f"windows verify: {len(new)} rows, committed {len(old)}")
    for a, b in zip(new, old):
        for k in ("n", "position", "orbits", "on_pattern", "verdict"):
            if a[k] != b[k]:
                fail(f"windows verify n={b['n']} {b['position']} {k}: {a[k]} != committed {b[k]}")
        if not close(a["r"], b["r"], 1e-9):
            fail(f"windows verify n={b['n']} {b['position']} r: {a['r']} != committed {b['r']}")
    print(f"ok: windows verify n = 2..20 ({len(new)} rows)")


def check_atlas(btob, root, tmp):
    # The committed atlas goes to L = 12; the words up to 8 symbols must come out the same.
    out = os.path.join(tmp, "atlas")
    run(btob, "pattern", "atlas", "--max-length", "8", "--no-check", "--no-plot", "--out", out)
    new = {(r["word"], i): r for i, r in enumerate(rows(os.path.join(out, "atlas.csv")))}
    old = [r for r in rows(os.path.join(root, "results/patterns/atlas.csv")) if symbols(btob, r["word"]) <= 8]
    new_list = list(new.values())
    if len(new_list) != len(old):
        fail(f"pattern atlas L <= 8: {len(new_list)} intervals, committed {len(old)}")
    for b in old:
        match = [a for a in new_list if a["word"] == b["word"] and close(a["r_low"], b["r_low"], 1e-9)]
        if not match:
            fail(f"pattern atlas: {b['word']} [{b['r_low']}, {b['r_high']}] not reproduced")
            continue
        a = match[0]
        if not close(a["r_high"], b["r_high"], 1e-9) or a["low_reason"] != b["low_reason"] or \
                a["high_reason"] != b["high_reason"]:
            fail(f"pattern atlas {b['word']}: {a} != committed {b}")
    print(f"ok: pattern atlas, words up to 8 symbols ({len(old)} intervals)")


def check_correlation(btob, root, tmp):
    out = os.path.join(tmp, "stats")
    new, old = rerun(btob, ["run", os.path.join(root, "analyses/scenes/stats_correlation_periodic.toml"), "--out", out],
                     os.path.join(out, "correlation_periodic_r0.15.csv"),
                     os.path.join(root, "results/stats/correlation_periodic_r0.15.csv"), "C_N periodic", "lags")
    bad = [(b["lag"], a["C_N"], b["C_N"]) for a, b in zip(new, old) if not close(a["C_N"], b["C_N"], 1e-9)]
    for lag, x, y in bad[:5]:
        fail(f"C_N periodic lag {lag}: {x} != committed {y}")
    print(f"ok: C_N on the sink 1133 at r = 0.15 ({len(new)} lags)")


def check_basins_r(btob, root, tmp):
    out = os.path.join(tmp, "basins_r")
    new, old = rerun(btob, ["basins-r", "--table", "--grid", "random:2000", "--seed", "1", "--out", out, "--quiet",
                            "--no-plot"],
                     os.path.join(out, "table_6_1_comparison.csv"),
                     os.path.join(root, "results/attractors/basins_r/table_6_1_comparison.csv"), "basins-r", "r values")
    for a, b in zip(new, old):
        if abs(float(a["periodic_fraction"]) - float(b["periodic_fraction"])) > 0.035:
            fail(f"basins-r r={b['r']}: periodic fraction {a['periodic_fraction']} vs committed {b['periodic_fraction']}")
        if a["paper_patterns_found"] != b["paper_patterns_found"]:
            fail(f"basins-r r={b['r']}: Table 6.1 patterns found {a['paper_patterns_found']} vs committed "
                 f"{b['paper_patterns_found']}")
    print(f"ok: basin fractions at the {len(new)} r values of Table 6.1")


def check_lyapunov_map(btob, root, tmp):
    out = os.path.join(tmp, "lyapunov")
    new, old = rerun(btob, ["run", os.path.join(root, "analyses/scenes/lyapunov_map.toml"), "--out", out],
                     os.path.join(out, "lyapunov_map_summary.csv"),
                     os.path.join(root, "results/lyapunov/lyapunov_map_summary.csv"), "lyapunov map", "r values")
    if len(new) != len(old):
        return
    off = sum(abs(float(a["lambda1_median"]) - float(b["lambda1_median"])) > 0.02 for a, b in zip(new, old))
    if off > 0.02 * len(old):
        fail(f"lyapunov map: median exponent differs by > 0.02 at {off} of {len(old)} r values (allowed 2%)")
    print(f"ok: Lyapunov map, {len(old)} r values ({off} with median differing by > 0.02)")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: results_check.py PATH/TO/btob REPO_ROOT")
    btob, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        check_window_bounds(btob, root)
        check_window_verify(btob, root, tmp)
        check_atlas(btob, root, tmp)
        check_correlation(btob, root, tmp)
        check_basins_r(btob, root, tmp)
        check_lyapunov_map(btob, root, tmp)
    if failures:
        print(f"results_check: {len(failures)} failure(s)")
        sys.exit(1)
    print("results_check: the committed results are reproduced")


if __name__ == "__main__":
    main()
