#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every CSV the command line writes loads as it is.

Runs each command that writes a CSV (files or stdout) on a small input into a temporary folder, then reads every
CSV it finds there twice: with numpy.genfromtxt(names=True, delimiter=",", dtype=None) and with Python's csv
module.  A CSV passes when it has one header line (no "#" line above it), every row has as many fields as the
header (csv module), numpy reads the same number of columns and rows, numpy's field names are the header's
(up to the '.' numpy drops), and, in what the command line writes now, no cell spells a non-number ("nan", "inf":
an undefined value is an empty cell, which numpy reads as nan).  It also checks that two `basins` runs with different --name in one folder keep both
fraction tables (the old fractions.csv ignored --name).  `btob precision` is left out (its smallest run takes ~30 s): its
CSV is checked by PrecisionTradeoff in tests/test_long_precision.cpp.

Usage: cli_csv.py PATH/TO/btob [REPO_ROOT]   exit 0 when every CSV passes, 1 otherwise (each failure printed); with
REPO_ROOT, the CSVs committed under results/ and analyses/ are checked too.
"""
import csv
import glob
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def run(btob, args, stdout_to=None):
    p = subprocess.run([btob, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(f"btob {' '.join(args)} exited {p.returncode}: {p.stderr.strip()[-300:]}")
    elif stdout_to:
        with open(stdout_to, "w") as f:
            f.write(p.stdout)


def check_csv(path, numbers_or_empty=False):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        fail(f"{path}: empty")
        return
    header = rows[0]
    if header[0].startswith("#"):
        fail(f"{path}: a comment line above the header: {','.join(header)[:80]}")
        return
    ragged = [i + 1 for i, r in enumerate(rows) if len(r) != len(header)]
    if ragged:
        fail(f"{path}: lines {ragged[:5]} have a field count other than the header's {len(header)}")
        return
    if numbers_or_empty:
        spelled = [(i + 1, c) for i, r in enumerate(rows[1:], 1) for c in r
                   if c.strip().lower() in ("nan", "-nan", "inf", "-inf", "+inf", "infinity", "-infinity")]
        if spelled:
            fail(f"{path}: cells that spell a non-number (an undefined value is an empty cell): {spelled[:5]}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy's own deprecation notices, not about the file
        try:
            a = np.genfromtxt(path, names=True, delimiter=",", dtype=None, encoding="utf-8", invalid_raise=True)
        except Exception as e:  # noqa: BLE001 -- any failure to load is the finding
            fail(f"{path}: numpy.genfromtxt(names=True) fails: {str(e).splitlines()[0]}")
            return
    names = a.dtype.names or ()
    if list(names) != [h.replace(".", "") for h in header]:
        fail(f"{path}: numpy names {list(names)[:6]}... differ from the header {header[:6]}...")
    n = a.size if a.ndim else 1
    if len(rows) > 1 and n != len(rows) - 1:
        fail(f"{path}: numpy reads {n} rows, the csv module {len(rows) - 1}")


def check_h5(path):
    """Every dataset carries its units, axes and a one-line description, and every string attribute
    (datasets' and the file's) reads as str, not bytes."""
    import h5py
    with h5py.File(path, "r") as f:
        for k, v in f.attrs.items():
            if isinstance(v, bytes):
                fail(f"{path}: file attribute {k} reads as bytes")
        datasets = []
        f.visititems(lambda name, obj: datasets.append((name, obj)) if isinstance(obj, h5py.Dataset) else None)
        for name, ds in datasets:
            for key in ("units", "axes", "description"):
                v = ds.attrs.get(key)
                if v is None:
                    fail(f"{path}: dataset {name} has no attribute {key}")
                elif not isinstance(v, str):
                    fail(f"{path}: dataset {name}: attribute {key} reads as {type(v).__name__}, not str")
                elif key != "axes" and not v.strip():
                    fail(f"{path}: dataset {name}: attribute {key} is empty")
            for k, v in ds.attrs.items():
                # CLASS and NAME are the HDF5 dimension-scale standard's own fixed-length ASCII attributes (H5DS)
                if isinstance(v, bytes) and k not in ("CLASS", "NAME"):
                    fail(f"{path}: dataset {name}: attribute {k} reads as bytes")
    return len(datasets)


# CSVs of commands not yet moved to empty cells for undefined values: they may still spell "nan".
SPELLS_NAN = set()  # generated CSVs allowed to spell nan: none


def commands(d):
    """(arguments, file to hold stdout or None): one small run of every command that writes a CSV."""
    q = ["--no-plot", "--quiet"]
    return [
        (["basins", "--r", "0.21", "--grid", "strip:12x12", "--replicates", "1", "--out", f"{d}/basins", *q], None),
        (["basins", "--r", "0.15", "--grid", "strip:8x8", "--replicates", "0", "--out", f"{d}/basins", "--name",
          "second", *q], None),
        (["basins-r", "--r-values", "0.15,0.2", "--grid", "random:16", "--out", f"{d}/basins_r", *q], None),
        (["classify", "--r", "0.2", "--point", "1,0.8,-1"], f"{d}/classify.csv"),
        (["correlate", "--r", "0.11", "--n-max", "50", "--iterations", "2000", "--fit-lags", "50", "--method", "both",
          "--out", f"{d}/corr", *q], None),
        (["measure", "--r", "0.15", "--iterations", "200", "--transient", "10", "--bins", "8", "--out", f"{d}/measure",
          *q], None),
        (["lyapunov", "--r", "0.15", "--point", "1,-3,-1.1", "--iterations", "2000", "--convergence",
          f"{d}/lyapunov_convergence.csv"], f"{d}/lyapunov.csv"),
        (["lyapunov", "--r", "0.15", "--point", "1,-3,-1.1", "--iterations", "2000", "--weighted"],
         f"{d}/lyapunov_weighted.csv"),
        (["lyapunov-map", "--r-min", "0.1", "--r-max", "0.2", "--r-count", "4", "--iterations", "500", "--transient",
          "50", "--out", f"{d}/lmap", *q], None),
        (["hyperbolicity-orbits", "--r-min", "0.1", "--r-max", "0.2", "--r-count", "3", "--grid", "random:4",
          "--iterations", "200", "--transient", "200", "--backward", "200", "--out", f"{d}/hyp", *q], None),
        (["particles", "1133", "--r", "0.15", "--periods", "20", "--out", f"{d}/particles", "--header", "--no-plot"],
         f"{d}/particles_stdout.csv"),
        (["particles", "132312", "--r", "0.5", "--periods", "5", "--out", f"{d}/particles_fail", "--no-plot"], None),
        (["pattern-curves", "--word", "132312", "--r-count", "50", "--out", f"{d}/curves", "--no-plot"], None),
        (["strip-orbits", "--r", "0.2", "--orbits", "3", "--iterations", "600", "--tail", "100", "--out",
          f"{d}/strip", "--no-plot"], None),
        (["transfer", "--r", "0.21", "--boxes", "16x16", "--samples", "4", "--eigenvalues", "4", "--measure-orbits",
          "2", "--measure-iterations", "200", "--tv-bins", "8", "--cycle", "1133", "--out", f"{d}/transfer",
          "--no-plot"], None),
        (["transfer-r", "--r-min", "0.15", "--r-max", "0.2", "--r-count", "2", "--boxes", "8x8", "--samples", "4",
          "--eigenvalues", "4", "--out", f"{d}/transfer_r", "--no-plot"], None),
        (["pattern", "atlas", "--max-length", "4", "--out", f"{d}/atlas", *q], None),
        (["pattern", "132^2", "--window"], f"{d}/pattern_window.csv"),
        (["windows", "bounds", "--n", "1..4", "--certify"], f"{d}/bounds.csv"),
        (["windows", "thresholds"], f"{d}/thresholds.csv"),
        (["windows", "stripes", "--max-m", "8"], f"{d}/stripes.csv"),
        (["windows", "verify", "--n", "2..3", "--iterations", "2000", "--per-n", "10", "--tail", "100", "--out",
          f"{d}/verify", *q], None),
        (["windows", "precision", "--n", "1..3", "--out", f"{d}/wprec", *q], None),
    ]


def main():
    btob = sys.argv[1]
    if len(sys.argv) > 2:  # the committed CSVs of the repository at sys.argv[2] (results/, analyses/), as they are
        root = sys.argv[2]
        listed = subprocess.run(["git", "-C", root, "ls-files", "results/*.csv", "analyses/*.csv"],
                                stdout=subprocess.PIPE, text=True, check=True).stdout.split()
        for f in listed:
            check_csv(os.path.join(root, f))
        print(f"{len(listed)} committed CSV files checked, {len(failures)} failure(s)")
    with tempfile.TemporaryDirectory() as d:
        for args, stdout_to in commands(d):
            run(btob, args, stdout_to)
        for name in ("basins_fractions.csv", "second_fractions.csv"):
            if not os.path.exists(os.path.join(d, "basins", name)):
                fail(f"basins: {name} missing (two runs with different --name in one folder)")
        files = sorted(glob.glob(os.path.join(d, "**", "*.csv"), recursive=True))
        for f in files:
            check_csv(f, numbers_or_empty=os.path.basename(f) not in SPELLS_NAN)
        print(f"{len(files)} CSV files checked, {len(failures)} failure(s)")
        h5 = sorted(glob.glob(os.path.join(d, "**", "*.h5"), recursive=True))
        n = sum(check_h5(f) for f in h5)
        print(f"{len(h5)} HDF5 files ({n} datasets) checked, {len(failures)} failure(s) in all")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
