#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Whether two builds of btob give the same results: every committed manifest (results/**/NAME.json that records a
request) is run by both executables with `btob run NAME.json --out DIR --no-plot`, and every file they write is
compared: HDF5 datasets bitwise (tests/h5_same_data.py's rule: attributes hold provenance and are not compared),
CSV tables cell for cell and every other file but the manifest byte for byte, leaving out datasets and columns of
wall time or throughput (named "...seconds..." or "..._per_second"), and standard output byte for byte but for times
in seconds and the output folder's name.  A refactor that claims "behaviour
unchanged, bit for bit" shows this table.

Usage: same_results.py BTOB_BEFORE BTOB_AFTER [--only SUBSTRING ...] [--skip SUBSTRING ...] [--set KEY=VALUE ...]
                       [--work DIR]
  --set KEY=VALUE   overrides a field of every manifest it applies to (both builds alike), for a smaller run of an
                    expensive result (e.g. --set max-length=8 for the pattern atlas): the row says so.
Prints one row per manifest (same / differs / failed, with the time of each run) and exits 1 when any differs.
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def manifests(only, skip):
    for path in sorted(glob.glob(os.path.join(ROOT, "results", "**", "*.json"), recursive=True)):
        rel = os.path.relpath(path, ROOT)
        if only and not any(s in rel for s in only):
            continue
        if any(s in rel for s in skip):
            continue
        try:
            with open(path) as f:
                j = json.load(f)
        except (OSError, ValueError):
            continue
        if isinstance(j, dict) and isinstance(j.get("request"), dict) and "command" in j["request"]:
            yield rel, j


def with_overrides(j, sets):
    """The manifest with each KEY=VALUE override applied to the request's fields it has; the keys applied."""
    args = dict(j["request"]["args"])
    applied = []
    for kv in sets:
        k, v = kv.split("=", 1)
        if k in args:
            args[k] = v
            applied.append(kv)
    out = dict(j)
    out["request"] = {"command": j["request"]["command"], "args": args}
    return out, applied


def run(btob, manifest, out):
    t0 = time.monotonic()
    p = subprocess.run([btob, "run", manifest, "--out", out, "--no-plot", "--quiet"], capture_output=True, text=True)
    return p, time.monotonic() - t0


def timed(name):
    """A dataset or CSV column that measures the run, not the result: its wall time ("...seconds...") or a
    throughput ("..._per_second": the precision study's iterations_per_second)."""
    return "seconds" in name or "per_second" in name


def h5_differences(pa, pb):
    """The datasets of two HDF5 files that differ bitwise (tests/h5_same_data.py's rule), wall times left out."""
    import h5py
    sys.path.insert(0, os.path.join(ROOT, "tests"))
    from h5_same_data import datasets, raw
    with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
        da, db = datasets(fa), datasets(fb)
        bad = [f"{k} only in one" for k in sorted(set(da) ^ set(db))]
        for k in sorted(set(da) & set(db)):
            if timed(k):
                continue
            x, y = da[k], db[k]
            if x.dtype != y.dtype or x.shape != y.shape or raw(x) != raw(y):
                bad.append(f"{k} differs")
        return bad


def csv_rows(path):
    """A CSV's rows without its columns of wall time."""
    import csv
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, h in enumerate(rows[0]) if not timed(h)] if rows else []
    return [[row[i] for i in keep if i < len(row)] for row in rows]


def same_files(a, b):
    """Differences between the files of two output folders (manifests and figures left out)."""
    bad = []
    names = sorted(set(os.listdir(a)) | set(os.listdir(b)))
    for n in names:
        if n.endswith((".json", ".png", ".gif")):
            continue
        pa, pb = os.path.join(a, n), os.path.join(b, n)
        if not (os.path.exists(pa) and os.path.exists(pb)):
            bad.append(f"{n} only in one")
        elif n.endswith(".h5"):
            bad += [f"{n}: {d}" for d in h5_differences(pa, pb)]
        elif n.endswith(".csv"):
            if csv_rows(pa) != csv_rows(pb):
                bad.append(f"{n} differs")
        elif open(pa, "rb").read() != open(pb, "rb").read():
            bad.append(f"{n} differs")
    return bad


def stdout_text(text, d, side):
    """Standard output with what may differ between two runs of the same request: the output folder's name, times
    in seconds ("(3.4 s)") and a printed table's columns of wall time."""
    import csv
    import io
    text = text.replace(os.path.join(d, side), "OUT")
    text = re.sub(r"[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)? s\b", "T s", text)
    rows = list(csv.reader(io.StringIO(text)))
    if rows and any(timed(h) for h in rows[0]):  # a CSV table with a column of wall time
        keep = [i for i, h in enumerate(rows[0]) if not timed(h)]
        return [[row[i] for i in keep if i < len(row)] for row in rows]
    return text


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--only", action="append", default=[])
    ap.add_argument("--skip", action="append", default=[])
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--work", default="/tmp/btob_same_results")
    o = ap.parse_args()
    differ = 0
    for rel, j in manifests(o.only, o.skip):
        j, applied = with_overrides(j, o.set)
        tag = rel.replace("/", "_")[:-5]
        d = os.path.join(o.work, tag)
        os.makedirs(d, exist_ok=True)
        m = os.path.join(d, "manifest.json")
        with open(m, "w") as f:
            json.dump(j, f)
        (pa, ta), (pb, tb) = run(o.before, m, os.path.join(d, "before")), run(o.after, m, os.path.join(d, "after"))
        note = f" ({', '.join(applied)})" if applied else ""
        if pa.returncode or pb.returncode:
            verdict = f"failed: {pa.returncode}/{pb.returncode} {(pa.stderr or pb.stderr).strip()[-160:]}"
            differ += pa.returncode != pb.returncode
        else:
            bad = same_files(os.path.join(d, "before"), os.path.join(d, "after"))
            if stdout_text(pa.stdout, d, "before") != stdout_text(pb.stdout, d, "after"):
                bad.append("stdout differs")
            verdict = "same" if not bad else "DIFFERS: " + "; ".join(bad)
            differ += bool(bad)
        print(f"{rel}\t{j['request']['command']}{note}\t{ta:.1f} s / {tb:.1f} s\t{verdict}", flush=True)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
