# SPDX-License-Identifier: GPL-3.0-or-later
"""Round trips of every request: Python's res.save(d), then `btob run d/NAME.json`, gives the same data bitwise (every
HDF5 dataset, every CSV table); the result's `command` attribute, evaluated, gives the same data again; save()
writes the figure wherever the command line draws one, and writes nothing when it cannot.

The requests are enumerated from the binding (btob._btob._commands), so a request added to the binding without a
small case here fails test_every_request_has_a_case."""
import glob
import os
import subprocess

import h5py
import numpy as np
import pytest

import btob
from conftest import exe

P = (1.0, -0.5, -1.1)
# Requests left out, each with its reason (a new request must be given a case or a reason).
SLOW = {"precision_study": "about 30 s at its smallest (fixed MPFR references); python_test_long_precision compares "
                           "it with the command line"}
# Attributes that say how and when a result was made, not what it is (parts of their names).
VOLATILE = ("date", "command", "seconds", "per_second", "threads", "git", "compiler", "version", "dirty", "flags",
            "host", "name")
# One small request per function, each well under a second.
CASES = {
    "bifurcation": dict(r_min=0.1, r_max=0.12, r_count=12, iterations=300, tail=20, bins=32, overlay=[],
                        attractors=True),
    "lyapunov": dict(r=0.2, point=P, iterations=2000, transient=100),
    "lyapunov_map": dict(r_min=0.1, r_max=0.2, r_count=4, grid="random:3", iterations=500, transient=100,
                         attractors=True),
    "lyapunov_strip": dict(r=0.3, grid="strip:6x4", iterations=400, transient=100),
    "hyperbolicity": dict(r=0.2, grid="strip:8x6"),
    "hyperbolicity_orbits": dict(r_min=0.1, r_max=0.2, r_count=2, grid="random:2", iterations=200, transient=50,
                                 backward=50),
    "classify": dict(r=0.2, point=P),
    "basins": dict(r=0.2, grid="strip:8x6", replicates=1, transient=500, iterations=300, lyap_iterations=400,
                   lyap_transient=100),
    "basins_r": dict(r_values=[0.2, 0.3], grid="random:6", transient=500, iterations=300, lyap_iterations=400,
                     lyap_transient=100, boundary_grid="sphere:24x20"),
    "correlate": dict(r=0.11, point=P, n_max=20, iterations=2000),
    "measure": dict(r=0.2, grid="random:3", iterations=1000, transient=100, bins=8),
    "windows_poly": dict(n="1..2"),
    "windows_bounds": dict(n="2..4", digits=20),
    "windows_thresholds": dict(digits=20),
    "windows_stripes": dict(max_m=6, digits=20),
    "windows_verify": dict(n="2..3", iterations=1000, per_n=0, tail=500),
    "windows_precision": dict(n="1..2", mpfr_digits=20),
    "pattern": dict(word="132312", r=0.2),
    "pattern_atlas": dict(max_length=4, no_check=True),
    "pattern_curves": dict(word="132312", r_min=0.3, r_max=0.6, r_count=20),
    "strip_orbits": dict(r=0.2, orbits=2, iterations=400, tail=50),
    "leaves": dict(r=0.25, grid="sphere:6x6", transient=300, iterations=300, lyap_iterations=400, lyap_transient=50,
                   labels=[0.5, 1.2], leaf_iterations=500),
    "transfer": dict(r=0.15, boxes="16x16", samples=4, eigenvalues=4, tv_bins=16, measure_orbits=2,
                     measure_iterations=500),
    "transfer_r": dict(r_min=0.2, r_max=0.3, r_count=2, boxes="16x16", samples=4, eigenvalues=4),
    "particles": dict(word="1133", r=0.15, periods=20, diagram_periods=2),
}


def test_every_request_has_a_case():
    assert not set(CASES) & set(SLOW)
    assert sorted([*CASES, *SLOW]) == sorted(btob._btob._commands), "a bound request without a round-trip case"


def untimed(text):
    """A CSV's rows without its columns of wall time (headers containing 'seconds')."""
    import csv
    rows = list(csv.reader(text.decode().splitlines()))
    keep = [i for i, h in enumerate(rows[0]) if "seconds" not in h] if rows else []
    return [[row[i] for i in keep if i < len(row)] for row in rows]


def same_files(a, b, skip=(".json", ".png", ".gif")):
    """Every data file of folder a equals b's: HDF5 datasets bitwise, CSV and text byte for byte."""
    names = sorted(f for f in os.listdir(a) if not f.endswith(skip))
    assert names == sorted(f for f in os.listdir(b) if not f.endswith(skip))
    assert names, f"no data files in {a}"
    for n in names:
        pa, pb = os.path.join(a, n), os.path.join(b, n)
        if n.endswith(".h5"):
            with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
                assert sorted(fa) == sorted(fb), n
                if not len(fa):  # a verdict (classify): its attributes are the data; provenance and timings differ
                    def data(f):
                        return {k: v for k, v in f.attrs.items()
                                if not any(w in k for w in VOLATILE) and k not in ("scalar_type", "kind", "title")}
                    assert data(fa) == data(fb), n
                for k in fa:
                    if "seconds" in k:  # wall time of the run (windows_precision), not the result
                        continue
                    x, y = fa[k][()], fb[k][()]
                    if x.dtype == object:  # strings (exact decimals, word names): compare the texts
                        assert list(x) == list(y), f"{n}:{k}"
                    else:
                        assert x.tobytes() == y.tobytes(), f"{n}:{k}"
        else:
            with open(pa, "rb") as fa, open(pb, "rb") as fb:
                ta, tb = fa.read(), fb.read()
            if n.endswith(".csv"):  # timing columns measure the run, not the result
                assert untimed(ta) == untimed(tb), n
            else:
                assert ta == tb, n


def same_arrays(x, y):
    assert x.arrays == y.arrays
    for k in x.arrays:
        if "seconds" in k:  # wall time of the run
            continue
        assert np.asarray(getattr(x, k)).tobytes() == np.asarray(getattr(y, k)).tobytes(), k
    for k in x.decimals + x.texts:
        assert getattr(x, k) == getattr(y, k), k


@pytest.mark.parametrize("function", sorted(CASES))
def test_save_then_run_is_bitwise(function, tmp_path):
    res = getattr(btob, function)(threads=1, **CASES[function])
    saved, rerun = tmp_path / "saved", tmp_path / "rerun"
    # The figure is drawn where the command line draws one (the others have no script).
    written = res.save(saved, plot=res.plot_script != "" and function in ("basins", "lyapunov_strip"))
    assert all(os.path.exists(p) for p in written)
    if function in ("basins", "lyapunov_strip"):
        assert glob.glob(str(saved / "*.png")), f"{function}: save() wrote no figure"
    name = res.attrs["name"]
    manifest = saved / f"{name}.json"
    assert manifest.exists()
    p = subprocess.run([exe(), "run", str(manifest), "--out", str(rerun), "--quiet", "--threads", "1", "--no-plot"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    same_files(saved, rerun)
    # The command attribute is a call that reproduces the result.
    again = eval(res.attrs["command"], {"btob": btob})
    same_arrays(res, again)


def test_save_writes_nothing_when_the_figure_fails(tmp_path, monkeypatch):
    res = btob.basins(r=0.2, grid="strip:6x4", transient=300, iterations=300, lyap_iterations=400, lyap_transient=50)
    monkeypatch.setenv("BTOB_PYTHON", "/bin/false")  # the plot script's interpreter fails
    with pytest.raises(RuntimeError, match="nothing was written"):
        res.save(tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_the_command_line_recorded_runs_again_in_a_shell(tmp_path):
    """The manifest's `command` of a run whose flags hold shell characters (a point list with ';', a title with
    spaces and a quote, an empty value) pasted into a shell writes the same data again."""
    import json
    import shutil
    out = tmp_path / "a"
    args = [exe(), "lyapunov-map", "--r-min", "0.1", "--r-max", "0.2", "--r-count", "2", "--grid",
            "1,-0.5,-1.1;1,0.2,-1", "--iterations", "300", "--transient", "50", "--title", "it's a title",
            "--out", str(out), "--no-plot", "--quiet", "--threads", "1"]
    assert subprocess.run(args).returncode == 0
    shutil.copytree(out, tmp_path / "first")
    with open(out / "lyapunov_map.json") as f:
        command = json.load(f)["command"]
    p = subprocess.run(["bash", "-c", command], capture_output=True, text=True)
    assert p.returncode == 0, (command, p.stderr)
    same_files(tmp_path / "first", out)
