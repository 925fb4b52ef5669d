"""btob.precision_study against `btob precision` (about 30 s each: the study's Lyapunov and window checks have
fixed sizes), hence labelled long: the deterministic columns of tradeoff.csv and the manifest's attributes."""
import csv
import io

import btob
from conftest import cli, manifest
from test_requests import compare_attrs


def test_precision_study_attrs(tmp_path):
    kw = dict(orbits=2, iterations=200, r=[0.2], window_n=[2, 3])
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
