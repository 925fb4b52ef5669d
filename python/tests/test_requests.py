# SPDX-License-Identifier: GPL-3.0-or-later
"""Python and the command line give bit-identical numbers for the same request: every function of the package
against `btob COMMAND` with the same flags, on small requests (a second or two each).  Arrays are compared
bitwise (dtype, shape and every bit, NaN included); attributes by value, except those that record when, how fast
and from which command line the result was made."""
import csv
from decimal import Decimal
import glob
import io
import math
import os

import h5py
import numpy as np
import pytest

import btob
from conftest import cli, manifest

# Attributes that differ between two runs of the same request by nature.
VOLATILE = {"date_utc", "command", "total_seconds", "threads"}


def volatile(key):
    return key in VOLATILE or key in PRESENTATION or "seconds" in key or key.endswith("_rate") or key in ("points_per_second",)


def same_array(a, b):
    a, b = np.asarray(a), np.asarray(b)
    assert a.dtype == b.dtype and a.shape == b.shape, (a.dtype, b.dtype, a.shape, b.shape)
    assert a.tobytes() == b.tobytes()


def compare_h5(res, path):
    """Every dataset of the command line's HDF5 file equals the Python array of the same name bitwise, the
    Python result has no array the file lacks, and the attributes agree."""
    with h5py.File(path, "r") as f:
        assert sorted(f.keys()) == sorted(res.arrays + res.texts + res.decimals)
        for k in res.arrays:
            same_array(getattr(res, k), f[k][...])
        for k in res.texts:  # names as data: strings
            assert getattr(res, k) == list(f[k].asstr()[...]), k
        for k in res.decimals:  # exact decimals: the same text (None where the result has no value)
            assert [None if v is None else str(v) for v in getattr(res, k)] == \
                [None if v == "" else v for v in f[k].asstr()[...]], k
        file_attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    compare_attrs(res.attrs, file_attrs)


def compare_attrs(py, other):
    keys = {k for k in set(py) | set(other) if not volatile(k)}
    for k in sorted(keys):
        assert k in py and k in other, f"attribute {k}: python {k in py}, command line {k in other}"
        a, b = py[k], other[k]
        if isinstance(a, float) and math.isnan(a):
            assert math.isnan(b), k
        else:
            assert a == b, f"attribute {k}: python {a!r}, command line {b!r}"


# (function, command, keyword arguments): small requests of every file-writing function.
H5_CASES = [
    ("bifurcation", "bifurcation",
     dict(r_min=0.1, r_max=0.12, r_count=40, iterations=400, tail=40, bins=64, overlay=["thresholds", "windows"],
          raw=True)),
    ("bifurcation", "bifurcation",
     dict(r_min=0.0717, r_max=0.08, r_count=20, iterations=300, tail=30, log=True, precision="float", grid="random:5")),
    ("lyapunov_map", "lyapunov-map",
     dict(r_min=0.1, r_max=0.2, r_count=8, grid="random:4", iterations=1000, transient=100)),
    ("lyapunov_strip", "lyapunov-strip", dict(r=0.3, grid="strip:8x5", iterations=800, transient=100)),
    ("hyperbolicity", "hyperbolicity", dict(r=0.2, grid="strip:16x8")),
    ("hyperbolicity_orbits", "hyperbolicity-orbits",
     dict(r_min=0.1, r_max=0.2, r_count=3, grid="random:3", iterations=300, transient=100, backward=100)),
    ("basins", "basins", dict(r=0.2, grid="strip:12x10", replicates=1, transient=500, iterations=300,
                              lyap_iterations=400, lyap_transient=100)),
    ("basins_r", "basins-r", dict(r_values=[0.2, 0.3], grid="random:12", transient=500, iterations=300,
                                  lyap_iterations=400, lyap_transient=100, boundary_grid="sphere:24x20")),
    ("correlate", "correlate", dict(r=0.11, point=(1.0, -0.5, -1.1), n_max=40, iterations=4000, method="both")),
    ("measure", "measure", dict(r=0.2, grid="random:3", iterations=2000, transient=100, bins=16)),
    ("pattern_curves", "pattern-curves", dict(word="132312", r_min=0.2, r_max=0.6, r_count=50)),
    ("pattern_atlas", "pattern atlas", dict(max_length=5, no_check=True)),
    ("strip_orbits", "strip-orbits", dict(r=0.2, orbits=3, iterations=600, tail=100)),
]
# Attributes only the command line's figure needs (strip-orbits: plot-w1, only).
PRESENTATION = {"plot_w1", "only"}


@pytest.mark.parametrize("function,command,kwargs", H5_CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(H5_CASES)])
def test_hdf5_bitwise(function, command, kwargs, tmp_path):
    cli(command, kwargs, out=tmp_path)
    h5 = glob.glob(str(tmp_path / "*.h5"))
    assert len(h5) == 1
    res = getattr(btob, function)(**kwargs)
    compare_h5(res, h5[0])
    # The manifest holds the same attributes (and the request).
    js = manifest(h5[0][:-3] + ".json")
    js.pop("request")
    compare_attrs(res.attrs, js)


def rows(text):
    return list(csv.DictReader(io.StringIO("\n".join(l for l in text.splitlines() if not l.startswith("#")))))


def test_lyapunov_orbit_matches_stdout():
    kw = dict(r=0.15, point=(1.0, -0.5, -1.1), iterations=20000, transient=500, weighted=True)
    row = rows(cli("lyapunov", kw))[0]
    res = btob.lyapunov(**kw)
    for k, fmt in [("lambda1_weighted", ".15g"), ("lambda2_weighted", ".15g")]:
        assert format(getattr(res, k), fmt) == row[k], k
    for k, e in [("lambda1", "err1"), ("lambda2", "err2")]:  # core::with_error: the interval holds the value
        assert contains(row[k], row[e], getattr(res, k)) and Decimal(row[e]) >= Decimal(getattr(res, e)), k
    assert res.iterations == int(row["iterations"])


def contains(value, error, x):
    """Whether the printed interval value +- error contains the double x (exact decimal arithmetic)."""
    return Decimal(value) - Decimal(error) <= Decimal(x) <= Decimal(value) + Decimal(error)


def test_lyapunov_convergence_table_is_the_command_lines(tmp_path):
    """The running averages that `btob lyapunov --convergence FILE` writes are arrays of every Python result, and
    convergence=FILE writes the same file from Python (one declaration, commands::Spec::also_write)."""
    kw = dict(r=0.11, point=(1.0, -0.5, -1.1), iterations=5000, transient=200)
    cli("lyapunov", kw, extra=["--convergence", str(tmp_path / "c.csv")])
    table = np.genfromtxt(tmp_path / "c.csv", delimiter=",", names=True, comments="#")
    res = btob.lyapunov(**kw)
    assert res.convergence_n.dtype == np.uint64 and res.convergence_n.tolist() == table["n"].astype(int).tolist()
    for k in ("lambda1", "lambda2"):
        got = [float(format(x, ".12g")) for x in getattr(res, "convergence_" + k)]
        assert got == table[k].tolist(), k
    assert res.convergence_n[-1] == kw["iterations"]
    btob.lyapunov(convergence=str(tmp_path / "p.csv"), **kw)
    assert (tmp_path / "p.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()


def test_lyapunov_mpfr_matches_stdout():
    kw = dict(r=0.2, point=(1.0, 0.8, -1.0), iterations=2000, transient=100, precision="mpfr:30")
    row = rows(cli("lyapunov", kw))[0]
    res = btob.lyapunov(**kw)
    assert contains(row["lambda1"], row["err1"], res.lambda1) and contains(row["lambda2"], row["err2"], res.lambda2)


def test_classify_matches_stdout():
    kw = dict(r=0.2, point=(1.0, 0.8, -1.0))
    row = rows(cli("classify", kw))[0]
    res = btob.classify(**kw)
    assert res.type == row["type"] and res.pattern == row["pattern"] and str(res.period) == row["period"]
    assert contains(row["lambda1"], row["batch_err"], res.lambda1) and Decimal(row["batch_err"]) >= Decimal(res.batch_err)
    # The CSV carries the detail as core::csv_text writes text fields (no character that would need quoting).
    csv_text = res.detail.replace(",", ";").replace('"', "'").replace("\n", " ").replace("#", "no.")
    assert csv_text == row["detail"]


def test_windows_bounds_exact_decimals():
    kw = dict(n="1..6", digits=30, certify=True)
    table = rows(cli("windows bounds", kw))
    res = btob.windows_bounds(**kw)
    assert [str(d) for d in res.lower_bound_decimal] == [r["lower_bound"] for r in table]
    assert [("" if d is None else str(d)) for d in res.upper_bound_decimal] == [r["upper_bound"] for r in table]
    assert [str(d) for d in res.a_decimal] == [r["a"] for r in table]
    # The decimals are Decimal, not rounded to double: 30 digits survive.
    assert len(str(res.lower_bound_decimal[0]).split(".")[1]) == 30
    assert float(res.lower_bound_decimal[1]) == res.lower_bound[1]
    same_array(res.n, np.arange(1, 7, dtype=np.uint32))


def test_windows_thresholds_and_stripes():
    table = rows(cli("windows thresholds", dict(digits=40)))
    res = btob.windows_thresholds(digits=40)
    assert [str(d) for d in res.value_decimal] == [r["value"] for r in table]
    same_array(res.value, np.array([float(r["value"]) for r in table]))
    table = rows(cli("windows stripes", dict(max_m=12, digits=25)))
    res = btob.windows_stripes(max_m=12, digits=25)
    assert [str(d) for d in res.r_decimal] == [r["r"] for r in table]
    same_array(res.m, np.array([int(r["m"]) for r in table], dtype=np.uint32))


def test_pattern_verdict_and_charpoly_match_stdout():
    out = cli("pattern 132312", {"r": "0.5"})
    res = btob.pattern(word="132312", r="0.5")
    lines = {l.split()[0]: l for l in out.splitlines() if l.strip()}
    # The command prints the digits the route vouches for (the next wider type confirms them): the stored double
    # rounds to the printed text within half a unit of its last digit.
    printed = lines["mu1"].split()[1]
    mantissa = printed.lower().split("e")[0].lstrip("-")
    digits = len(mantissa.replace(".", "").lstrip("0"))
    exponent = int(f"{float(printed):e}".split("e")[1])
    assert digits >= 10 and abs(float(printed) - float(res.eigen_re[0])) <= 0.5 * 10.0 ** (exponent - digits + 1)
    assert res.verdict in lines["verdict"] and res.letters in lines["letters"]
    out = cli("pattern 132312", {"charpoly": True})
    res = btob.pattern(word="132312", charpoly=True)
    for k in ("c2", "c1", "c0", "discriminant"):
        assert getattr(res, k) and getattr(res, k) in out, k
    with pytest.raises(TypeError, match="missing required keyword argument 'word'"):
        btob.pattern(r="0.5")


def test_windows_poly_text():
    text = cli("windows poly", dict(n="1..2"))
    res = btob.windows_poly(n="1..2")
    for n in (1, 2):
        assert f"Q_{n} = {getattr(res, f'Q_{n}_developed')}" in text or getattr(res, f"Q_{n}_developed") in text
        assert getattr(res, f"Q_{n}_factorised") in text


def test_windows_verify_csv(tmp_path):
    kw = dict(n="2..3", iterations=2000, per_n=0, tail=1000)
    cli("windows verify", kw, out=tmp_path)
    table = rows(open(glob.glob(str(tmp_path / "*.csv"))[0]).read())
    res = btob.windows_verify(**kw)
    assert [int(r["on_pattern"]) for r in table] == res.on_pattern.tolist()
    assert [float(r["r"]) for r in table] == res.r.tolist()
    compare_attrs(res.attrs, {k: v for k, v in manifest(glob.glob(str(tmp_path / "*.json"))[0]).items()
                              if k not in ("request", "name")} | {"name": res.attrs["name"]})


def test_windows_precision_values(tmp_path):
    kw = dict(n="1..3", mpfr_digits=20)
    cli("windows precision", kw, out=tmp_path)
    table = rows(open(str(tmp_path / "precision.csv")).read())
    res = btob.windows_precision(**kw)
    flat = res.value.ravel().tolist()
    assert len(flat) == len(table)
    assert all(float(r["value"]) == v or (math.isnan(v) and r["value"] in ("nan", "NaN")) for r, v in zip(table, flat))
    compare_attrs(res.attrs, {k: v for k, v in manifest(str(tmp_path / "precision.json")).items() if k != "request"})


def test_save_writes_what_the_command_line_replays(tmp_path):
    """res.save writes NAME.h5, NAME.json and the summary table like the command line; `btob run NAME.json`
    reproduces the arrays and the table byte for byte."""
    import subprocess
    from conftest import exe
    res = btob.lyapunov_map(r_min=0.1, r_max=0.2, r_count=5, grid="random:3", iterations=600, transient=60)
    written = res.save(tmp_path / "a", name="mine", plot=False)
    assert sorted(os.path.basename(w) for w in written) == ["mine.h5", "mine.json", "mine_summary.csv"]
    p = subprocess.run([exe(), "run", str(tmp_path / "a" / "mine.json"), "--out", str(tmp_path / "b"), "--no-plot",
                        "--quiet"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    with h5py.File(tmp_path / "b" / "mine.h5", "r") as f:
        for k in res.arrays:
            same_array(getattr(res, k), f[k][...])
    assert (tmp_path / "a" / "mine_summary.csv").read_bytes() == (tmp_path / "b" / "mine_summary.csv").read_bytes()


# The tables that moved from the command line into their results' tables() (correlate, measure): save() writes them
# with the command line's bytes.  The precision study's table is compared in test_long_precision.py (a run takes 30 s).
TABLE_CASES = [
    ("correlate", "correlate", dict(r=0.2, iterations=3000, n_max=300, observable="theta,w2", method="both")),
    ("measure", "measure", dict(r=0.11, grid="random:6", iterations=1000, bins=10)),
]


@pytest.mark.parametrize("function,command,kwargs", TABLE_CASES, ids=[c[0] for c in TABLE_CASES])
def test_moved_tables_are_the_command_lines(function, command, kwargs, tmp_path):
    res = getattr(btob, function)(**kwargs)
    name = res.attrs["name"]
    cli(command, kwargs, out=tmp_path / "cli", extra=["--name", name])
    saved = [f for f in res.save(tmp_path / "py", name=name, plot=False) if f.endswith(".csv")]
    assert saved and sorted(os.path.basename(f) for f in saved) == sorted(res.tables)
    for f in saved:
        assert open(f).read() == (tmp_path / "cli" / os.path.basename(f)).read_text(), f
