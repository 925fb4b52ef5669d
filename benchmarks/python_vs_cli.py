#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""btob.bifurcation against `btob bifurcation` on the Figure 4.1 workload (5000 r x 32 orbits x 5000 iterations,
700 bins), alternated A B A B ... in one run: the iteration time each reports (`iteration_seconds`, the kernel's
wall time: what the binding could slow down) and the wall time of the whole call.  The goal: the Python
iteration time to be within 5% of the command line's.  The machine is shared: quote the ratio of medians of one run.

Usage: PYTHONPATH=build/release/python python3 benchmarks/python_vs_cli.py [BTOB_BINARY] [REPEATS] [OUT.csv]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import btob

FIG41 = dict(r_min=0.0717, r_max=0.1717, r_count=5000, iterations=5000, tail=100, bins=700)


def flags(kw):
    out = []
    for k, v in kw.items():
        out += ["--" + k.replace("_", "-"), str(v)]
    return out


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else "build/release/btob"
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    out = sys.argv[3] if len(sys.argv) > 3 else None
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for rep in range(1, repeats + 1):
            t0 = time.monotonic()
            subprocess.run([exe, "bifurcation", *flags(FIG41), "--threads", "2", "--no-plot", "--quiet", "--out", d,
                            "--name", "cli"], check=True)
            wall = time.monotonic() - t0
            with open(os.path.join(d, "cli.json")) as f:
                rows.append(("cli", rep, json.load(f)["iteration_seconds"], wall))
            t0 = time.monotonic()
            res = btob.bifurcation(threads=2, **FIG41)
            wall = time.monotonic() - t0
            rows.append(("python", rep, float(res.attrs["iteration_seconds"]), wall))
            del res
    med = {w: statistics.median(r[2] for r in rows if r[0] == w) for w in ("cli", "python")}
    wall = {w: statistics.median(r[3] for r in rows if r[0] == w) for w in ("cli", "python")}
    text = "route,rep,iteration_seconds,wall_seconds\n" + "".join(f"{a},{b},{c:.4f},{e:.4f}\n" for a, b, c, e in rows)
    if out:
        with open(out + ".tmp", "w") as f:
            f.write(text)
        os.replace(out + ".tmp", out)
    print(text, end="")
    print(f"median iteration time python / cli = {med['python'] / med['cli']:.3f} "
          f"({med['python']:.3f} s / {med['cli']:.3f} s); whole call {wall['python'] / wall['cli']:.3f} "
          f"(the command line's includes starting the process and writing the HDF5 file)")


if __name__ == "__main__":
    main()
