# SPDX-License-Identifier: GPL-3.0-or-later
"""btob.precision_study against `btob precision` (about 30 s each: the study's Lyapunov and window checks have
fixed sizes), hence labelled long: the deterministic columns of tradeoff.csv and the manifest's attributes."""
import csv
import io
import os
import shutil
import subprocess
import sys

import btob
from conftest import cli, manifest
from test_requests import compare_attrs


def test_precision_study_attrs(tmp_path):
    kw = dict(orbits=2, iterations=200, r_values=[0.2], window_n=[2, 3])
    cli("precision", kw, out=tmp_path)
    res = btob.precision_study(**kw)
    compare_attrs(res.attrs, {k: v for k, v in manifest(str(tmp_path / "tradeoff.json")).items() if k != "request"})
    table = [l for l in open(str(tmp_path / "tradeoff.csv")).read().splitlines() if not l.startswith("#")]
    t = list(csv.DictReader(io.StringIO("\n".join(table))))
    assert [r["method"] for r in t] == res.methods.split(",")
    # The deterministic columns (the speed column is a measurement of each run).
    assert [float(r["decimal_digits"]) for r in t] == res.decimal_digits.tolist()
    assert [float(r["agree_min_r0.2"]) for r in t] == res.agree_min.ravel().tolist()
    assert [float(r["window_n_max"] or -1) for r in t] == res.window_n_max.tolist()
    # save() writes tradeoff.csv through the result's tables(), as the command line does: the same bytes but for
    # the speed column.
    saved = [f for f in res.save(tmp_path / "py", name="tradeoff", plot=False) if f.endswith(".csv")]
    assert [os.path.basename(f) for f in saved] == ["tradeoff.csv"]
    a = list(csv.reader(open(saved[0])))
    b = list(csv.reader(open(tmp_path / "tradeoff.csv")))
    col = b[0].index("iterations_per_second")
    assert a[0] == b[0] and len(a) == len(b) > 1
    assert [r[:col] + r[col + 1:] for r in a] == [r[:col] + r[col + 1:] for r in b]
    # The command's figure from its HDF5 file alone (the script's own Table B.1 aside), and Python's plot() of the
    # same result: the methods are a string dataset, the iterations an attribute.
    alone = tmp_path / "alone"
    alone.mkdir()
    shutil.copy(tmp_path / "tradeoff.h5", alone / "tradeoff.h5")
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    p = subprocess.run([sys.executable, os.path.join(root, "analyses", "plot", "precision_tradeoff.py"),
                        str(alone / "tradeoff.h5"), str(alone / "tradeoff.png")], capture_output=True, text=True, cwd=alone)
    assert p.returncode == 0 and (alone / "tradeoff.png").stat().st_size > 10000, p.stderr
    fig = res.plot()
    assert len(fig.axes) == 4 and "(200 iterations compared)" in fig.axes[0].get_title()
