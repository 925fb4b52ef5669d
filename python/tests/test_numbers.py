# SPDX-License-Identifier: GPL-3.0-or-later
"""Every number keeps the digits it was computed to and says what it is (docs/reference/numbers.md): decimals
computed beyond double reach NAME.h5, Python (decimal.Decimal) and the CSV with every digit, and `btob run` of the
manifest gives the same digits; each carries its status (certified, estimated, conjectured); a value printed with
its error bar is printed so that the interval contains the stored value; --out writes the CSV tables the command
prints."""
import csv
import io
import os
import subprocess
from decimal import Decimal

import h5py
import pytest

import btob
from conftest import cli, exe, flags

STATUSES = {"certified", "estimated", "conjectured"}


def rows(text):
    return list(csv.DictReader(io.StringIO(text)))


def save(command, kwargs, out):
    """`btob COMMAND ... --out OUT` for a command that prints its result (no --no-plot: it has no figure)."""
    p = subprocess.run([exe(), *command.split(), *flags(kwargs), "--out", str(out), "--quiet", "--threads", "1"],
                       capture_output=True, text=True, timeout=240)
    assert p.returncode == 0, p.stderr


def rerun(manifest, out):
    p = subprocess.run([exe(), "run", str(manifest), "--out", str(out), "--quiet", "--threads", "1"],
                       capture_output=True, text=True, timeout=240)
    assert p.returncode == 0, p.stderr


def decimals_of(path, name):
    with h5py.File(path, "r") as f:
        return [Decimal(s.decode() if isinstance(s, bytes) else s) if s else None for s in f[name][()]]


def status_of(path, name):
    with h5py.File(path, "r") as f:
        return {k: str(v) for k, v in f[name].attrs.items() if k in ("status", "basis", "confidence")}


def test_pattern_window_digits_reach_file_python_csv_and_run(tmp_path):
    """The issue's case: `pattern 132312 --window --digits 30 --out D` stored r_low as float64 and no decimal."""
    kw = dict(window=True, digits=30)
    printed = rows(cli("pattern 132312", kw))
    assert printed and all(r["status"] == "estimated" for r in printed)
    save("pattern 132312", kw, tmp_path / "d")
    h5 = tmp_path / "d" / "pattern.h5"
    lows = decimals_of(h5, "r_low_decimal")
    assert lows == [Decimal(r["r_low"]) for r in printed]
    assert decimals_of(h5, "r_high_decimal") == [Decimal(r["r_high"]) for r in printed]
    # 30 significant digits survive: more than a double holds (17), so they cannot come from r_low's float64.
    assert all(len(d.as_tuple().digits) >= 25 for d in lows)
    with h5py.File(h5, "r") as f:
        # The doubles are the MPFR values rounded once; 30 digits rounded to double may differ by one ulp.
        assert all(abs(float(d) - x) <= 2.3e-16 * x for d, x in zip(lows, f["r_low"][()]))
    assert status_of(h5, "r_low_decimal")["status"] == "estimated" and status_of(h5, "r_low")["status"] == "estimated"
    assert status_of(h5, "r_low_decimal")["confidence"]
    with open(tmp_path / "d" / "pattern.csv") as fh:  # --out writes the table the command prints
        assert rows(fh.read()) == printed
    res = btob.pattern(word="132312", **kw)
    assert "r_low_decimal" in res.decimals and "r_high_decimal" in res.decimals
    assert res.r_low_decimal == lows and all(isinstance(d, Decimal) for d in res.r_low_decimal)
    assert res.status["r_high_decimal"]["status"] == "estimated"
    rerun(tmp_path / "d" / "pattern.json", tmp_path / "e")
    assert decimals_of(tmp_path / "e" / "pattern.h5", "r_low_decimal") == lows


def test_certified_bounds_say_what_each_bound_is(tmp_path):
    """windows bounds --certify: the lower bound is certified by its certificate, the upper bound r_crit,2(n) is the
    paper's conjecture, in the CSV, NAME.h5, Python and after `btob run`."""
    kw = dict(n="1..6", digits=30, certify=True)
    printed = rows(cli("windows bounds", kw))
    assert [r["lower_status"] for r in printed] == ["certified"] * 6
    assert [r["upper_status"] for r in printed] == [""] + ["conjectured"] * 5  # n = 1 has no upper bound
    save("windows bounds", kw, tmp_path / "d")
    h5 = tmp_path / "d" / "bounds.h5"
    with open(tmp_path / "d" / "bounds.csv") as fh:
        assert rows(fh.read()) == printed
    lower = decimals_of(h5, "lower_bound_decimal")
    assert lower == [Decimal(r["lower_bound"]) for r in printed]
    for name, want in [("lower_bound_decimal", "certified"), ("lower_bound", "certified"), ("a_decimal", "certified"),
                       ("upper_bound_decimal", "conjectured"), ("upper_bound", "conjectured")]:
        st = status_of(h5, name)
        assert st["status"] == want and st["basis"], name
    assert "sturm_roots_a_b" in status_of(h5, "lower_bound")["basis"]
    res = btob.windows_bounds(**kw)
    assert res.status["upper_bound_decimal"]["status"] == "conjectured"
    assert res.status["lower_bound_decimal"]["status"] == "certified"
    rerun(tmp_path / "d" / "bounds.json", tmp_path / "e")
    assert decimals_of(tmp_path / "e" / "bounds.h5", "lower_bound_decimal") == lower
    assert decimals_of(tmp_path / "e" / "bounds.h5", "upper_bound_decimal") == decimals_of(h5, "upper_bound_decimal")
    # Without --certify the same digits are an estimate, not a certified number.
    assert {r["lower_status"] for r in rows(cli("windows bounds", dict(n="2..3", digits=15)))} == {"estimated"}


def test_verdict_decimals_keep_the_precision(tmp_path):
    """A verdict in MPFR keeps its eigenvalues' and orbit's digits in NAME.h5 (the doubles are views)."""
    save("pattern 1133", dict(r="0.15", precision="mpfr:40"), tmp_path / "d")
    h5 = tmp_path / "d" / "pattern.h5"
    re = decimals_of(h5, "eigen_re_decimal")
    assert len(re) == 3 and len(re[0].as_tuple().digits) > 30
    assert len(decimals_of(h5, "orbit_decimal")) == 3 * 4
    assert status_of(h5, "eigen_re_decimal")["status"] == "estimated"
    assert "mpfr" in status_of(h5, "eigen_re_decimal")["basis"]


ORBITS = [(0.15, "1,-0.5,-1.1"), (0.2, "1,-0.5,-1.1"), (0.11, "1,-3,-1.1"), (0.3, "1,0.8,-1"), (0.5, "1,-0.5,-1.1"),
          (0.0718, "1,-0.5,-1.1")]


@pytest.mark.parametrize("r,point", ORBITS)
def test_printed_lyapunov_interval_contains_the_stored_value(r, point, tmp_path):
    """The issue's case (r = 0.15 from 1,-0.5,-1.1: the 1133 sink) printed -0.468347380336 +- 8.88e-16, which
    excludes the stored -0.4683473803358724; the printed interval must contain the value NAME.h5 holds."""
    kw = dict(r=r, point=point, iterations=20000, transient=500)
    row = rows(cli("lyapunov", kw))[0]
    save("lyapunov", kw, tmp_path / "d")
    with h5py.File(tmp_path / "d" / "lyapunov.h5", "r") as f:
        for k, e in (("lambda1", "err1"), ("lambda2", "err2")):
            stored = Decimal(float(f.attrs[k]))  # the double's exact value
            v, err = Decimal(row[k]), Decimal(row[e])
            assert v - err <= stored <= v + err, (k, row[k], row[e], stored)
            assert Decimal(float(f.attrs[e])) <= err  # the printed bar is the stored one rounded up
            assert f.attrs[f"{k}.status"] == "estimated" and f.attrs[f"{k}.confidence"]
    with open(tmp_path / "d" / "lyapunov.csv") as fh:
        assert rows(fh.read()) == [row]


@pytest.mark.parametrize("r,point", [(0.15, "1,-0.5,-1.1"), (0.2, "1,0.8,-1"), (0.5, "1,-0.5,-1.1")])
def test_classify_and_lyapunov_bars_agree_on_one_orbit(r, point):
    """classify's bar is named for what it is, batch_err (lyapunov's batch means floored at the rounding; at
    r = 0.5 on the P2 invariant curves classify printed lambda1 = 0.0002152 with err 4.3e-05, excluding 0 and
    lyapunov's 8.7e-06: the finite-time bias of a 4000-step average is not in a batch-means error): its printed
    interval contains the value, a cycle's is never of zero width, and it agrees with lyapunov's estimate of the
    same orbit within their combined bars plus, for an average, the finite-time floor 10/n both verdicts use."""
    c = rows(cli("classify", dict(r=r, point=point)))[0]
    res = btob.classify(r=r, point=point)
    v, err = Decimal(c["lambda1"]), Decimal(c["batch_err"])
    assert v - err <= Decimal(res.lambda1) <= v + err
    assert res.batch_err > 0  # a bar of zero width claims every digit of a double
    assert res.status["lambda1"]["status"] == "estimated"
    ly = btob.lyapunov(r=r, point=point, iterations=100000, transient=1000)
    # A cycle's exponent is exact up to rounding: lyapunov's average of the same orbit lies within three combined
    # bars (no finite-time floor); an orbit measured by pass 2 has classify's finite-time floor 10/n besides.
    finite = 0 if res.type in ("periodic", "collapse") else 10 / res.attrs["lyap_iterations"]
    bar = 3 * (res.batch_err ** 2 + ly.err1 ** 2) ** 0.5 + finite
    assert abs(res.lambda1 - ly.lambda1) <= bar, (res.type, res.lambda1, res.batch_err, ly.lambda1, ly.err1)


STDOUT_TABLES = {
    "windows bounds": (["windows", "bounds", "--n", "1..4"], "bounds.csv"),
    "windows thresholds": (["windows", "thresholds"], "thresholds.csv"),
    "windows stripes": (["windows", "stripes", "--max-m", "12"], "stripes.csv"),
    "lyapunov": (["lyapunov", "--r", "0.2", "--point", "1,-0.5,-1.1", "--iterations", "2000"], "lyapunov.csv"),
    "pattern --window": (["pattern", "1133", "--window"], "pattern.csv"),
    "classify": (["classify", "--r", "0.2", "--point", "1,-0.5,-1.1"], "classify.csv"),
}


@pytest.mark.parametrize("command", sorted(STDOUT_TABLES))
def test_out_writes_the_printed_table(command, tmp_path):
    """--help promises `--out` writes "NAME.h5, the CSV tables and NAME.json": the CSV is the table printed."""
    args, name = STDOUT_TABLES[command]
    printed = subprocess.run([exe(), *args, "--threads", "1"], capture_output=True, text=True, timeout=240)
    assert printed.returncode == 0, printed.stderr
    p = subprocess.run([exe(), *args, "--threads", "1", "--out", str(tmp_path), "--quiet"], capture_output=True,
                       text=True, timeout=240)
    assert p.returncode == 0, p.stderr
    assert name in os.listdir(tmp_path), sorted(os.listdir(tmp_path))
    with open(tmp_path / name) as fh:
        assert fh.read() == printed.stdout
