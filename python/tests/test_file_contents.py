# SPDX-License-Identifier: GPL-3.0-or-later
"""Self-describing files: every file a command writes is opened and checked.  Every HDF5 dataset states its unit and
meaning (attributes units, description); every axis of a grid (a dataset of two or more dimensions) that runs over
a coordinate has that coordinate attached as an HDF5 dimension scale (index axes such as "initial condition" have
none); every CSV row has the header's width and ends with a newline; a manifest states each verdict once; the verdict
of an orbit the classifier could not decide is "undecided" in every name, string and cell, never a second word."""
import csv
import json
import os
import subprocess

import h5py
import pytest

from conftest import exe

# Axes that number things (an orbit, an attractor, an interval) rather than run over a coordinate, and the components
# of a point; a label may add what it holds in brackets ("step (the last tail iterations)" is a "step" axis).
INDEX_AXES = {"initial condition", "attractor", "attractor then undecided", "interval", "line", "(r, colour)", "step",
              "eigenvalue", "orbit", "group", "period", "event", "particle", "point of the periodic orbit",
              "cycle point", "(x, y, z)", "(a, b)"}


def axis_labels(axes):
    """The labels of an `axes` attribute, split at the commas outside brackets (io::axis_labels)."""
    labels, depth, start = [], 0, 0
    for i, ch in enumerate(axes + ","):
        if ch in "([":
            depth += 1
        elif ch in ")]" and depth > 0:
            depth -= 1
        elif ch == "," and depth == 0:
            labels.append(axes[start:i].strip())
            start = i + 1
    return [l for l in labels if l]


def is_index(label):
    return label in INDEX_AXES or label.split(" (")[0] in INDEX_AXES

COMMANDS = {
    "bifurcation": ["bifurcation", "--r-min", "0.1", "--r-max", "0.2", "--r-count", "8", "--iterations", "200",
                    "--tail", "20", "--bins", "16", "--overlay", "thresholds", "windows", "--attractors"],
    "basins": ["basins", "--r", "0.2", "--grid", "sphere:8x6", "--replicates", "1", "--transient", "300",
               "--iterations", "300", "--lyap-iterations", "400", "--lyap-transient", "50"],
    "lyapunov-strip": ["lyapunov-strip", "--r", "0.3", "--grid", "strip:6x4", "--iterations", "300",
                       "--transient", "50"],
    "lyapunov-map": ["lyapunov-map", "--r-min", "0.1", "--r-max", "0.2", "--r-count", "3", "--grid", "random:2",
                     "--iterations", "300", "--transient", "50", "--overlay", "thresholds", "--attractors"],
    "hyperbolicity": ["hyperbolicity", "--r", "0.2", "--grid", "strip:8x6"],
    "correlate": ["correlate", "--r", "0.11", "--point", "1,-0.5,-1.1", "--n-max", "20", "--iterations", "2000"],
    "pattern atlas": ["pattern", "atlas", "--max-length", "4", "--ics", "20", "--iterations", "400", "--tail", "100",
                      "--max-period", "50"],
    "pattern atlas --feasible": ["pattern", "atlas", "--feasible", "--max-length", "3"],
    "windows precision": ["windows", "precision", "--n", "2..4"],
    "transfer-r": ["transfer-r", "--r-min", "0.15", "--r-max", "0.3", "--r-count", "2", "--boxes", "8x8", "--samples",
                   "2", "--eigenvalues", "3"],
    "particles": ["particles", "1133", "--r", "0.15", "--periods", "3"],
    "basins-r": ["basins-r", "--r-values", "0.2,0.35", "--grid", "random:12", "--boundary-grid", "sphere:24x20",
                 "--transient", "50", "--iterations", "300", "--lyap-iterations", "200", "--lyap-transient", "50", "--refine-factor", "0"],
    "strip-orbits": ["strip-orbits", "--r", "0.2", "--orbits", "3", "--iterations", "400", "--tail", "100"],
    "transfer": ["transfer", "--r", "0.2", "--boxes", "8x8", "--samples", "2", "--eigenvalues", "3",
                 "--measure-orbits", "2", "--measure-iterations", "200", "--tv-bins", "4"],
    "hyperbolicity-orbits": ["hyperbolicity-orbits", "--r-count", "3", "--iterations", "300"],
    "measure": ["measure", "--r", "0.2", "--grid", "random:4", "--iterations", "300"],
    "pattern-curves": ["pattern-curves", "--r-count", "20"],
    "windows verify": ["windows", "verify", "--n", "2..4", "--iterations", "2000", "--tail", "500"],
    "leaves": ["leaves", "--r", "0.25", "--grid", "sphere:6x6", "--transient", "300", "--iterations", "300",
               "--lyap-iterations", "400", "--lyap-transient", "50", "--labels", "0.5,1.2", "--leaf-iterations", "500"],
}
# Commands without a plot: windows poly, and those that print their result and write files only when given --out.
NO_PLOT = {
    "windows poly": ["windows", "poly", "--n", "1..5"],
    "classify": ["classify", "--r", "0.2", "--point", "1,-0.5,-1.1"],
    "lyapunov": ["lyapunov", "--r", "0.2", "--point", "1,-0.5,-1.1", "--iterations", "1000"],
    "pattern": ["pattern", "132312", "--r", "0.5"],
    "pattern --window": ["pattern", "132312", "--window"],
    "pattern --window --digits": ["pattern", "132312", "--window", "--digits", "30"],
    "pattern mpfr": ["pattern", "1133", "--r", "0.15", "--precision", "mpfr:30"],
    "windows bounds": ["windows", "bounds", "--n", "1..5"],
    "windows bounds --certify": ["windows", "bounds", "--n", "1..5", "--certify", "--digits", "20"],
    "windows thresholds": ["windows", "thresholds"],
    "windows stripes": ["windows", "stripes"],
}


# The tables a plot script draws from, which NAME.h5 must hold beside its CSV files (the script reads NAME.h5 alone).
REQUIRED = {
    "pattern atlas": ["word", "r_low", "r_high", "low_reason", "high_reason", "detected_r", "detected_word",
                      "detected_status", "detected_count", "long_word", "long_r_low", "long_r_high", "missed_r",
                      "missed_word"],
    "pattern atlas --feasible": ["word", "stable", "count_r", "count_stable", "count_unstable", "count_feasible",
                                 "count_stable_collapse", "count_unstable_collapse"],
    "transfer-r": ["r", "re", "im", "peripheral_count", "gap", "p2_beta", "window_lower", "window_upper"],
    "windows precision": ["n", "precision", "route", "row", "abs_error", "seconds"],
    "particles": ["event_period", "event_time", "event_time_to_collapse", "event_x", "event_letter"],
}
# The verdict of an orbit no attractor was found for is "undecided" (attractors::type_name); this word, which files
# written before the rename used for it, must not reappear in a name, an attribute, a string or a CSV cell.
OLD_WORD = "unresolved"
# Names that are data (words, verdicts, reasons, collision letters) are string datasets, not numbers or CSV text.
TEXT_SUFFIXES = ("word", "status", "reason", "letter")


def check_h5(path, bad):
    with h5py.File(path, "r") as f:
        for name, ds in f.items():
            if not isinstance(ds, h5py.Dataset):
                continue
            if name.endswith(TEXT_SUFFIXES) and ds.dtype.kind not in "OSU":
                bad.append(f"{path}:{name}: a name that is data stored as {ds.dtype}, not as strings")
            for key in ("units", "description"):
                if not str(ds.attrs.get(key, "")):
                    bad.append(f"{path}:{name}: no {key}")
            if name.endswith("_decimal"):
                check_status(path, f, name, bad)
            if ds.ndim < 2:
                continue
            labels = axis_labels(str(ds.attrs.get("axes", "")))
            if len(labels) != ds.ndim:
                bad.append(f"{path}:{name}: axes '{ds.attrs.get('axes')}' do not name its {ds.ndim} dimensions")
                continue
            for i, label in enumerate(labels):
                if not is_index(label) and len(ds.dims[i]) == 0:
                    bad.append(f"{path}:{name}: axis {i} ({label}) has no dimension scale")


def check_status(path, f, name, bad):
    """A decimal (a number computed beyond double) says what it is, and so does its double twin
    (docs/reference/numbers.md): status certified, estimated or conjectured, its basis, and for an estimate the
    confidence of its bar."""
    twin = name.removesuffix("_decimal")
    for n in [name] + ([twin] if twin in f else []):
        a = f[n].attrs
        status = str(a.get("status", ""))
        if status not in ("certified", "estimated", "conjectured"):
            bad.append(f"{path}:{n}: status '{status}', not certified, estimated or conjectured")
        elif not str(a.get("basis", "")) or (status == "estimated" and not str(a.get("confidence", ""))):
            bad.append(f"{path}:{n}: status {status} without its basis or confidence")


def strings(value):
    """The strings an HDF5 attribute or dataset value holds (none for numbers)."""
    if isinstance(value, bytes):
        return [value.decode(errors="replace")]
    if isinstance(value, str):
        return [value]
    if hasattr(value, "dtype") and value.dtype.kind in "OSU":
        return [x for v in value.ravel().tolist() for x in strings(v)]
    return []


def check_word(path, bad):
    """Every name and string of the file (HDF5: objects, attribute names and string values, string datasets; CSV and
    JSON: the text) without OLD_WORD."""
    found = []
    if path.endswith(".h5"):
        with h5py.File(path, "r") as f:
            objects = [("/", f)]
            f.visititems(lambda name, obj: objects.append((name, obj)))
            for name, obj in objects:
                found += [name] if OLD_WORD in name.lower() else []
                for key, value in obj.attrs.items():
                    found += [f"{name}@{key}"] if any(OLD_WORD in s.lower() for s in [key, *strings(value)]) else []
                if isinstance(obj, h5py.Dataset) and any(OLD_WORD in s.lower() for s in strings(obj[()])):
                    found.append(f"{name} (values)")
    elif path.endswith((".csv", ".json")):
        with open(path) as f:
            found += [f"line {i}" for i, line in enumerate(f, start=1) if OLD_WORD in line.lower()]
    bad += [f"{path}: {where} says '{OLD_WORD}', not 'undecided'" for where in found]


def check_csv(path, bad):
    with open(path, newline="") as f:
        text = f.read()
    if text and not text.endswith("\n"):
        bad.append(f"{path}: the last row does not end with a newline")
    rows = list(csv.reader(text.splitlines()))
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != len(rows[0]):
            bad.append(f"{path}:{i}: {len(row)} fields, the header has {len(rows[0])}")


def check_manifest(path, bad):
    with open(path) as f:
        m = json.load(f)
    if "decays" in m and "decay_verdict" in m:
        bad.append(f"{path}: two verdicts (decays and decay_verdict)")


def run(args, out, plot=True):
    """Runs btob with args into the folder out (--no-plot where the command has a plot); returns its standard output."""
    p = subprocess.run([exe(), *args, "--out", str(out), "--quiet", "--threads", "1", *(["--no-plot"] if plot else [])],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p


@pytest.mark.parametrize("command", sorted(COMMANDS) + sorted(NO_PLOT))
def test_every_file_describes_itself(command, tmp_path):
    out = tmp_path / "out"
    p = run(COMMANDS[command], out) if command in COMMANDS else run(NO_PLOT[command], out, plot=False)
    if p.stdout:
        assert p.stdout.endswith("\n"), f"btob {command}: standard output does not end with a newline"
    bad = []
    files = sorted(os.listdir(out))
    assert files
    for name in files:
        path = str(out / name)
        check_word(path, bad)
        if name.endswith(".h5"):
            check_h5(path, bad)
        elif name.endswith(".csv"):
            check_csv(path, bad)
        elif name.endswith(".json"):
            check_manifest(path, bad)
    required = REQUIRED.get(command, [])
    if required:
        h5 = [name for name in files if name.endswith(".h5")]
        assert h5, f"btob {command}: no HDF5 file among {files}"
        with h5py.File(out / h5[0], "r") as f:
            bad += [f"{h5[0]}: no dataset {name}" for name in required if name not in f]
    assert not bad, "\n".join(bad)


def test_the_checks_catch_an_undescribed_grid(tmp_path):
    path = str(tmp_path / "x.h5")
    with h5py.File(path, "w") as f:
        f["image"] = [[1.0, 2.0], [3.0, 4.0]]
        f["image"].attrs["axes"] = "r, theta bin"
        f["image"].attrs["units"] = "count"
    with open(tmp_path / "x.csv", "w") as f:
        f.write("a,b\n1,2\n3")
    with h5py.File(path, "a") as f:
        f["word"] = [132.0]
    bad = []
    check_h5(path, bad)
    check_csv(str(tmp_path / "x.csv"), bad)
    assert any("no description" in b for b in bad) and any("no dimension scale" in b for b in bad)
    assert any("not as strings" in b for b in bad)
    assert any("newline" in b for b in bad) and any("fields" in b for b in bad)


def test_the_checks_catch_the_old_word(tmp_path):
    path = str(tmp_path / "x.h5")
    with h5py.File(path, "w") as f:
        f["fraction"] = [0.5]
        f["fraction"].attrs["axes"] = "attractor then unresolved"
        f.attrs["unresolved_fraction"] = 0.5
        f["name"] = [b"132^2", b"unresolved"]
    with open(tmp_path / "x.csv", "w") as f:
        f.write("attractor,type\n0,unresolved\n")
    bad = []
    check_word(path, bad)
    check_word(str(tmp_path / "x.csv"), bad)
    assert len(bad) == 4 and all("'unresolved'" in b for b in bad), bad


def test_string_arrays_describe_themselves_in_python():
    """res.info(name) describes a string array as it does an array (what the generated outputs pages list)."""
    import btob
    res = btob.pattern_atlas(max_length=4, no_check=True)
    assert "word" in res.texts and "word" not in res.arrays
    info = res.info("word")
    assert info["units"] == "word" and info["description"] and info["dims"] == (len(res.word),)
    assert "word" in dir(res)
