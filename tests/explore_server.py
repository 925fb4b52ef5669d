#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""`btob explore`'s HTTP interface: malformed and oversized requests get HTTP 400 and one line of JSON naming the
parameter, and the server keeps serving; a served command's answer (/api/run) is the record the command line
writes; the PNG of a view is the density of `btob bifurcation` with the same parameters, coloured by the rule of
explore.hpp (recomputed here from the HDF5 counts, an independent route through the colour and orientation stages);
nothing is served from the file system; export writes only into its folder.

Usage: explore_server.py BTOB
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from explore_common import png_indices, start_server, stop_server  # noqa: E402


def get(url, method="GET"):
    req = urllib.request.Request(url, method=method)
    try:
        with urllib.request.urlopen(req, timeout=60) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers, e.read()


def expect_400(base, path, field):
    status, headers, body = get(base + path)
    text = body.decode()
    assert status == 400, f"{path}: HTTP {status}, expected 400 ({text})"
    assert "\n" not in text.strip(), f"{path}: error of several lines: {text!r}"
    err = json.loads(text)["error"]
    assert err.startswith(field + ":"), f"{path}: error {err!r} does not name {field!r}"
    return err


def check_errors(base):
    view = "r_min=0.1&r_max=0.2&coord=theta&width=40&height=30"
    cases = [
        ("/api/bifurcation?r_max=0.2", "r_min"),
        ("/api/bifurcation?r_min=abc&r_max=0.2", "r_min"),
        ("/api/bifurcation?r_min=0.3&r_max=0.2", "r_max"),
        ("/api/bifurcation?r_min=0&r_max=0.2", "r_min"),
        ("/api/bifurcation?" + view.replace("width=40", "width=5000"), "width"),
        ("/api/bifurcation?" + view.replace("height=30", "height=0"), "height"),
        ("/api/bifurcation?" + view + "&iterations=1000000&grid=random:1000", "iterations"),  # over the work budget
        ("/api/bifurcation?" + view.replace("theta", "psi"), "coord"),
        ("/api/bifurcation?" + view + "&lo=0.5", "hi"),
        ("/api/bifurcation?" + view + "&lo=0.5&hi=0.1", "hi"),
        ("/api/bifurcation?" + view + "&tail=0", "tail"),
        ("/api/bifurcation?" + view + "&grid=strip:0x3", "grid"),
        ("/api/bifurcation?" + view + "&path=/etc/passwd", "path"),
        ("/api/bifurcation?" + view + "&session=" + "x" * 65, "session"),
        ("/api/run?r=0.15", "command"),
        ("/api/run?command=nothing&r=0.15", "command"),
        ("/api/run?command=lyapunov&r=0.15", "command"),  # declared, but it may write a file: not served
        ("/api/run?command=classify&point=1,-3,-1.1", "r"),
        ("/api/run?command=classify&r=0.15&point=1,2", "point"),
        ("/api/run?command=classify&r=0.15&point=1,-3,-1.1&path=/etc/passwd", "path"),
        ("/api/run?command=basins&r=0.15&grid=sphere:0x3", "grid"),
        ("/api/run?command=basins&r=0.15&replicates=101", "replicates"),
        ("/api/run?command=basins&r=0.15&replicates=x", "replicates"),
        ("/api/run?command=classify&r=0.15&point=1,-3,-1.1&session=a/b", "session"),
        # 1000 orbits x 600 kept states x (w1, w2): 1.2e6 array elements, over the answer's limit of 1e6
        ("/api/run?command=strip-orbits&r=0.2&orbits=1000&iterations=600&tail=600", "answer"),
        ("/api/tail?point=1,-3,-1.1", "r"),
        ("/api/tail?r=0.15&point=1,-3,-1.1&tail=0", "tail"),
        ("/api/overlays?r_min=0.1", "r_max"),
    ]
    for path, field in cases:
        expect_400(base, path, field)
    # Nothing of the file system is served: unknown pages and traversals are 404 with a JSON error.
    for path in ["/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/CMakeLists.txt", "/nothing.html"]:
        status, _, body = get(base + path)
        assert status in (400, 404), f"{path}: HTTP {status}"
        assert b"root:" not in body and "error" in json.loads(body.decode()), path
    print(f"explore_server: {len(cases)} bad requests answered 400 naming the parameter; no file served")


def expected_indices(density):
    """explore.hpp's rule: 0 for an empty bin, else 1 + round(254 log(1 + c) / log(1 + max c)); row 0 = hi."""
    R, B = len(density), len(density[0])
    top = max(max(col) for col in density)
    scale = 254 / math.log1p(top)  # as explore.cpp computes it, so both round the same double
    rows = []
    for b in reversed(range(B)):
        rows.append([0 if density[j][b] == 0 else 1 + int(scale * math.log1p(density[j][b]) + 0.5)
                     for j in range(R)])
    return rows


def check_png_is_the_density(btob, base, tmp):
    params = dict(r_min="0.12", r_max="0.18", coord="phi", lo="0", hi="3.2", width="64", height="48",
                  iterations="600", tail="40")
    q = "&".join(f"{k}={v}" for k, v in params.items())
    status, headers, body = get(base + "/api/bifurcation?" + q)
    assert status == 200 and headers["Content-Type"] == "image/png", status
    assert "compute;dur=" in headers["Server-Timing"], headers["Server-Timing"]
    w, h, got, _ = png_indices(body)
    assert (w, h) == (64, 48), (w, h)
    out = os.path.join(tmp, "ref")
    subprocess.run([btob, "bifurcation", "--r-min", "0.12", "--r-max", "0.18", "--r-count", "64", "--coord", "phi",
                    "--range", "0", "3.2", "--bins", "48", "--iterations", "600", "--tail", "40", "--out", out,
                    "--name", "ref", "--no-plot", "--quiet"], check=True)
    with h5py.File(os.path.join(out, "ref.h5")) as f:
        density = f["density"][()].tolist()
    want = expected_indices(density)
    bad = sum(g != w for gr, wr in zip(got, want) for g, w in zip(gr, wr))
    assert bad == 0, f"{bad} of {64 * 48} pixels differ from the density of btob bifurcation"
    assert sum(v > 0 for row in got for v in row) > 200, "the image is nearly empty"
    print("explore_server: the PNG is btob bifurcation's density of the same view, pixel for pixel")


def check_export(btob, base, export_dir, tmp):
    q = "r_min=0.15&r_max=0.16&coord=theta&width=30&height=20&iterations=300&tail=30&overlay=windows"
    status, _, body = get(base + "/api/export?" + q, method="POST")
    assert status == 200, body
    j = json.loads(body)
    assert sorted(os.listdir(export_dir)) == sorted([j["scene"], j["png"]]), os.listdir(export_dir)
    out = os.path.join(tmp, "rerun")
    subprocess.run([btob, "run", os.path.join(export_dir, j["scene"]), "--out", out, "--no-plot", "--quiet"],
                   check=True)
    h5 = [f for f in os.listdir(out) if f.endswith(".h5")][0]
    with h5py.File(os.path.join(out, h5)) as f:
        assert int(f["density"][()].sum()) == j["points_in_range"]
        assert f.attrs["r_min"] == 0.15 and f.attrs["r_max"] == 0.16
    print("explore_server: export wrote only its scene and PNG; btob run reproduces the view's density")


def check_run_is_the_command(btob, base, tmp):
    """/api/run answers the record the command line writes: classify's attributes and basins' labels and fractions
    equal those of NAME.json and NAME.h5 from `btob classify` / `btob basins` with the same fields, bit for bit."""
    status, _, body = get(base + "/api/run?command=classify&r=0.15&point=1,-3,-1.1")
    assert status == 200, body
    j = json.loads(body)
    out = os.path.join(tmp, "cmdline")
    subprocess.run([btob, "classify", "--r", "0.15", "--point", "1,-3,-1.1", "--out", out, "--name", "c", "--quiet"],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "c.json")) as f:
        want = json.load(f)
    for key in ["type", "pattern", "period", "lambda1", "batch_err", "detail", "iterations", "transient"]:
        assert j["attrs"][key] == want[key], (key, j["attrs"][key], want[key])
    assert j["command"] == "classify" and j["request"]["point"] == ["1,-3,-1.1"], j["request"]

    q = "command=basins&r=0.15&grid=sphere:24x20&replicates=0"
    status, _, body = get(base + "/api/run?" + q)
    assert status == 200, body
    j = json.loads(body)
    subprocess.run([btob, "basins", "--r", "0.15", "--grid", "sphere:24x20", "--replicates", "0", "--out", out,
                    "--name", "b", "--no-plot", "--quiet"], check=True)
    with h5py.File(os.path.join(out, "b.h5")) as f:
        labels = f["labels"][()]
        assert j["arrays"]["labels"]["dims"] == list(labels.shape) == [20, 24], j["arrays"]["labels"]["dims"]
        assert j["arrays"]["labels"]["data"] == labels.ravel().tolist()
        assert j["arrays"]["fraction"]["data"] == f["fraction"][()].tolist()
        assert j["attrs"]["undecided_fraction"] == f.attrs["undecided_fraction"]
    print(f"explore_server: /api/run answers btob classify's attributes and btob basins' {labels.size} labels and "
          f"{len(j['arrays']['fraction']['data'])} fractions exactly")


def check_cancel(base):
    """A newer request of a session cancels the session's running one (409), whose progress was visible."""
    long_view = "r_min=0.1&r_max=0.2&width=1000&height=100&iterations=120000&tail=10&session=s1"  # 3.8e9 iterations
    got = {}

    def run():
        t0 = time.time()
        got["status"], _, got["body"] = get(base + "/api/bifurcation?" + long_view)
        got["seconds"] = time.time() - t0

    t = threading.Thread(target=run)
    t.start()
    progress = {}
    for _ in range(200):  # until the run reports progress (at most 20 s on a loaded machine)
        time.sleep(0.1)
        progress = json.loads(get(base + "/api/progress?session=s1")[2])
        if progress.get("bifurcation", {}).get("total"):
            break
    assert progress.get("bifurcation", {}).get("total"), f"no progress reported: {progress}"
    status, _, _ = get(base + "/api/bifurcation?r_min=0.1&r_max=0.2&width=20&height=10&iterations=10&tail=5&session=s1")
    t.join()
    assert status == 200 and got["status"] == 409, (status, got)
    assert "cancelled" in json.loads(got["body"])["error"]
    print(f"explore_server: a newer request cancelled the running one after {got['seconds']:.2f} s (progress "
          f"{progress['bifurcation']['done']}/{progress['bifurcation']['total']} seen)")


def main(btob):
    with tempfile.TemporaryDirectory() as tmp:
        export_dir = os.path.join(tmp, "exports")
        proc, base = start_server(btob, export_dir, cwd=tmp)
        try:
            check_errors(base)
            check_png_is_the_density(btob, base, tmp)
            check_export(btob, base, export_dir, tmp)
            check_run_is_the_command(btob, base, tmp)
            check_cancel(base)
            check_errors(base)  # still serving after all of the above
            written = sorted(set(os.listdir(tmp)) - {"exports", "ref", "rerun", "cmdline"})
            assert written == [], f"the server wrote outside its export folder: {written}"
        finally:
            stop_server(proc)
    print("explore_server: ok")


if __name__ == "__main__":
    main(sys.argv[1])
