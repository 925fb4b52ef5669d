#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Quick mode of the runner (DESIGN.md): re-runs the cheap commands behind committed files of results/ into a
temporary directory and compares the numbers with the committed ones, within the tolerances stated below.

Usage: results_check.py PATH/TO/btob REPO_ROOT [CHECK...]
Exit 0 when every check passes, 1 otherwise (each failure printed with the file, row and both values).  A check
prints "ok:" only when it recorded no failure.  The first check, provenance, asks whether each committed
result's recorded commit could have produced it (see check_provenance).

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
import json
import os
import re
import subprocess
import sys
import tempfile

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def ok(before, msg):
    """Prints ok: msg only when no failure was recorded since `before` (len(failures) at the check's start)."""
    if len(failures) == before:
        print("ok:", msg)
    else:
        print(f"FAILED ({len(failures) - before} failure(s)):", msg)


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
    before = len(failures)
    # Table B.1 route: exact Q_n and MPFR roots, printed to 12 decimals -> identical text.
    new = rows(run(btob, "windows", "bounds", "--n", "1..100"), is_text=True)
    old = rows(os.path.join(root, "results/windows/bounds_certified.csv"))
    if len(new) != len(old):
        fail(f"windows bounds: {len(new)} rows, committed {len(old)}")
    for a, b in zip(new, old):
        for k in ("n", "lower_bound", "upper_bound"):
            if a[k] != b[k]:
                fail(f"windows bounds n={b['n']} {k}: {a[k]} != committed {b[k]}")
    ok(before, f"windows bounds n = 1..100 ({len(new)} rows)")


def check_window_verify(btob, root, tmp):
    before = len(failures)
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
    ok(before, f"windows verify n = 2..20 ({len(new)} rows)")


def check_atlas(btob, root, tmp):
    before = len(failures)
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
    ok(before, f"pattern atlas, words up to 8 symbols ({len(old)} intervals)")


def check_correlation(btob, root, tmp):
    before = len(failures)
    out = os.path.join(tmp, "stats")
    new, old = rerun(btob, ["run", os.path.join(root, "analyses/scenes/stats_correlation_periodic.toml"), "--out", out],
                     os.path.join(out, "correlation_periodic_r0.15.csv"),
                     os.path.join(root, "results/stats/correlation_periodic_r0.15.csv"), "C_N periodic", "lags")
    bad = [(b["lag"], a["C_N"], b["C_N"]) for a, b in zip(new, old) if not close(a["C_N"], b["C_N"], 1e-9)]
    for lag, x, y in bad[:5]:
        fail(f"C_N periodic lag {lag}: {x} != committed {y}")
    ok(before, f"C_N on the sink 1133 at r = 0.15 ({len(new)} lags)")


def check_basins_r(btob, root, tmp):
    before = len(failures)
    out = os.path.join(tmp, "basins_r")
    # The fractions are compared; the boundary geometry (a basins run per r) is left out of the quick re-run.
    new, old = rerun(btob, ["basins-r", "--table", "--grid", "random:2000", "--seed", "1", "--out", out, "--quiet",
                            "--boundary-grid", "none", "--no-plot"],
                     os.path.join(out, "table_6_1_comparison.csv"),
                     os.path.join(root, "results/attractors/basins_r/table_6_1_comparison.csv"), "basins-r", "r values")
    for a, b in zip(new, old):
        if abs(float(a["periodic_fraction"]) - float(b["periodic_fraction"])) > 0.035:
            fail(f"basins-r r={b['r']}: periodic fraction {a['periodic_fraction']} vs committed {b['periodic_fraction']}")
        if a["paper_patterns_found"] != b["paper_patterns_found"]:
            fail(f"basins-r r={b['r']}: Table 6.1 patterns found {a['paper_patterns_found']} vs committed "
                 f"{b['paper_patterns_found']}")
    ok(before, f"basin fractions at the {len(new)} r values of Table 6.1")


def check_lyapunov_map(btob, root, tmp):
    before = len(failures)
    out = os.path.join(tmp, "lyapunov")
    new, old = rerun(btob, ["run", os.path.join(root, "analyses/scenes/lyapunov_map.toml"), "--out", out],
                     os.path.join(out, "lyapunov_map_summary.csv"),
                     os.path.join(root, "results/lyapunov/lyapunov_map_summary.csv"), "lyapunov map", "r values")
    if len(new) != len(old):
        return
    off = sum(abs(float(a["lambda1_median"]) - float(b["lambda1_median"])) > 0.02 for a, b in zip(new, old))
    if off > 0.02 * len(old):
        fail(f"lyapunov map: median exponent differs by > 0.02 at {off} of {len(old)} r values (allowed 2%)")
    ok(before, f"Lyapunov map, {len(old)} r values ({off} with median differing by > 0.02)")


# ---- provenance: could the recorded commit have produced each committed result? -----------------------------
# Paths whose content is compiled into the binary: a result made by a binary of commit R is reproducible from the
# commit C that committed it only if these did not change between R and C.
CODE_PATHS = ["src", "cmake", "CMakeLists.txt"]


def git(root, *args, check=True):
    p = subprocess.run(["git", "-C", root, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if check and p.returncode != 0:
        raise RuntimeError(f"git {' '.join(args)}: {p.stderr.strip()}")
    return p


def last_commit(root, path):
    """The last commit that changed `path`, or None when it has uncommitted changes (or is untracked)."""
    if git(root, "status", "--porcelain", "--", path).stdout.strip():
        return None
    return git(root, "log", "-1", "--format=%H", "--", path).stdout.strip() or None


def is_ancestor(root, a, b):
    return git(root, "merge-base", "--is-ancestor", a, b, check=False).returncode == 0


def files_of(m):
    """The "files" a manifest lists (a JSON list or a comma-separated string), or None."""
    f = m.get("files")
    if f is None:
        return None
    return [x for x in (f if isinstance(f, list) else str(f).split(",")) if x]


def manifests_and_files(root):
    """Maps each manifest (a JSON object with git_commit under results/) to the committed files it describes:
    its "files" list when it has one, else the files of its folder whose name starts with the manifest's stem,
    and files that match no stem belong to every manifest of the folder.  Returns (groups, orphans): orphans are
    files of folders without any manifest."""
    # results/README.md (the gallery, written from the manifests), the README.md of a results folder (what its
    # results show, written by hand) and results/STALE are about results, not results.
    tracked = [f for f in git(root, "ls-files", "results").stdout.splitlines()
               if f and f != "results/STALE" and os.path.basename(f) != "README.md"]
    by_dir = {}
    for f in tracked:
        by_dir.setdefault(os.path.dirname(f), []).append(f)
    groups, orphans = {}, []
    for d, files in sorted(by_dir.items()):
        manifests = []
        for f in files:
            if not f.endswith(".json"):
                continue
            try:
                with open(os.path.join(root, f)) as fh:
                    m = json.load(fh)
            except (OSError, ValueError) as e:
                fail(f"provenance: {f}: unreadable JSON ({e})")
                continue
            if isinstance(m, dict) and "git_commit" in m:
                manifests.append((f, m))
        if not manifests:
            orphans += files
            continue
        listed = {os.path.join(d, x) for _, m in manifests for x in (files_of(m) or [])}
        for f, m in manifests:
            groups[f] = (m, [os.path.join(d, x) for x in (files_of(m) or [])])
        for f in files:
            if f in groups or f in listed:
                continue
            stem = os.path.splitext(os.path.basename(f))[0]
            owners = [mf for mf, m in manifests if files_of(m) is None and
                      stem.startswith(os.path.splitext(os.path.basename(mf))[0])]
            if owners:  # the longest matching stem owns it
                owners = [max(owners, key=len)]
            else:
                owners = [mf for mf, m in manifests if files_of(m) is None] or [mf for mf, _ in manifests]
            for mf in owners:
                groups[mf][1].append(f)
    return groups, orphans


def check_provenance(root):
    """Every committed result has a manifest, and its manifest's commit R could have produced it:
      1. R exists and is an ancestor of HEAD (a result cannot come from a commit this history does not have);
      2. the binary was built from a clean tree (git_dirty: no, recorded at build time) and, where recorded, the
         scripts and scenes were clean when it ran (run_dirty: no);
      3. the code compiled into the binary (src/, cmake/, CMakeLists.txt) is the same at R and at the commit C that
         last changed the manifest (a regeneration always rewrites it: date, seconds): otherwise the result sits
         beside code that R did not have;
      4. none of the result's files changed after C: a file edited or regenerated without its manifest is no
         longer what the manifest describes.
    A manifest or file with uncommitted changes is judged against HEAD and the working tree."""
    before = len(failures)
    if git(root, "rev-parse", "--is-inside-work-tree", check=False).returncode != 0:
        fail(f"provenance: {root} is not a git checkout: the committed results cannot be checked")
        return
    if git(root, "rev-parse", "--is-shallow-repository").stdout.strip() == "true":
        fail("provenance: shallow clone: the recorded commits cannot be checked (clone with full history)")
        return
    # results/STALE: results known to need regeneration, one path prefix per line with the reason (the debt is
    # written down, not hidden).  A listed result's provenance failures are reported, not counted; a listed prefix
    # that no longer fails is itself a failure (remove it from the list), and any unlisted failure fails.
    stale = {}
    stale_path = os.path.join(root, "results", "STALE")
    if os.path.exists(stale_path):
        with open(stale_path) as fh:
            for line in fh:
                line = line.strip()
                if line and not line.startswith("#"):
                    stale[line.split()[0]] = 0

    def pfail(path, msg):
        for prefix in stale:
            if path.startswith(prefix):
                stale[prefix] += 1
                print("stale (listed in results/STALE):", msg)
                return
        fail(msg)

    groups, orphans = manifests_and_files(root)
    for f in orphans:
        pfail(f, f"provenance: {f} has no manifest (a JSON with git_commit in its folder)")
    for mf, (m, files) in sorted(groups.items()):
        commit = str(m.get("git_commit", ""))
        if git(root, "rev-parse", "--verify", "--quiet", commit + "^{commit}", check=False).returncode != 0:
            pfail(mf, f"provenance: {mf}: git_commit '{commit}' is not a commit of this repository")
            continue
        if not is_ancestor(root, commit, "HEAD"):
            pfail(mf, f"provenance: {mf}: git_commit {commit} is not an ancestor of HEAD")
            continue
        if m.get("git_dirty") != "no":
            pfail(mf, f"provenance: {mf}: built from a tree with uncommitted changes (git_dirty: {m.get('git_dirty')})")
        if m.get("run_dirty", "no") != "no":
            pfail(mf, f"provenance: {mf}: scripts or scenes had uncommitted changes at run time (run_dirty: {m.get('run_dirty')})")
        c = last_commit(root, mf)
        diff = ["diff", "--name-only", commit] + ([c] if c else []) + ["--"] + CODE_PATHS
        changed = [x for x in git(root, *diff).stdout.splitlines() if x]
        if changed:
            pfail(mf, f"provenance: {mf}: recorded commit {commit[:12]} but the code changed before the result was "
                 f"committed ({c[:12] if c else 'working tree'}): {', '.join(changed[:4])}"
                 f"{' ...' if len(changed) > 4 else ''}; regenerate it from a clean build")
        for f in files:
            if not os.path.exists(os.path.join(root, f)):
                pfail(mf, f"provenance: {mf} lists {f}, which is missing")
                continue
            fc = last_commit(root, f)
            if c is None:
                continue  # the manifest itself is being regenerated: its files may change with it
            if fc is None:
                pfail(f, f"provenance: {f} has uncommitted changes but its manifest {mf} does not")
            elif not is_ancestor(root, fc, c):
                pfail(f, f"provenance: {f} changed in {fc[:12]}, after its manifest {mf} ({c[:12]})")
    for prefix, hits in stale.items():
        if hits == 0:
            fail(f"provenance: results/STALE lists {prefix}, whose provenance now holds: remove it from the list")
    listed = sum(stale.values())
    if listed:
        print(f"provenance: {listed} failure(s) of results listed in results/STALE (to regenerate)")
    ok(before, f"provenance of {len(groups)} manifests in results/")


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: results_check.py PATH/TO/btob REPO_ROOT [CHECK...]")
    btob, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    only = sys.argv[3:]  # optional check names, e.g. provenance (development)
    with tempfile.TemporaryDirectory() as tmp:
        checks = [("provenance", lambda: check_provenance(root)),
                  ("window_bounds", lambda: check_window_bounds(btob, root)),
                  ("window_verify", lambda: check_window_verify(btob, root, tmp)),
                  ("atlas", lambda: check_atlas(btob, root, tmp)),
                  ("correlation", lambda: check_correlation(btob, root, tmp)),
                  ("basins_r", lambda: check_basins_r(btob, root, tmp)),
                  ("lyapunov_map", lambda: check_lyapunov_map(btob, root, tmp))]
        for name, check in checks:
            if only and name not in only:
                continue
            try:
                check()
            except Exception as e:  # a missing or unreadable file, a crash of btob: a failure, not a traceback
                fail(f"{name}: {type(e).__name__}: {e}")
    if failures:
        print(f"results_check: {len(failures)} failure(s)")
        sys.exit(1)
    print("results_check: the committed results are reproduced")


if __name__ == "__main__":
    main()
