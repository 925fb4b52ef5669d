# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared helpers of the Python tests: the command line of the same build (BTOB_EXE, set by CTest) and the
translation of keyword arguments into its flags (the binding's rule backwards: '_' -> '-')."""
import json
import os
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def exe():
    e = os.environ.get("BTOB_EXE") or os.path.join(ROOT, "build", "release", "btob")
    if not os.path.exists(e):
        pytest.skip(f"no btob executable at {e}")
    return e


def flags(kwargs):
    """Keyword arguments as command-line flags: r_min=0.1 -> --r-min 0.1, True -> the bare flag, a point tuple ->
    x,y,z, a list -> several values."""
    out = []
    for k, v in kwargs.items():
        f = "--" + k.replace("_", "-")
        if v is True:
            out.append(f)
        elif v is False:
            continue
        elif isinstance(v, tuple):
            out += [f, ",".join(repr(float(x)).removesuffix(".0") for x in v)]  # the binding's shortest form
        elif isinstance(v, list):
            out += [f] + [str(x) for x in v]
        else:
            out += [f, str(v)]
    return out


def cli(command, kwargs, out=None, extra=()):
    """Runs `btob COMMAND` with the same request (and --out OUT --no-plot when OUT is given); returns stdout."""
    args = [exe()] + command.split() + flags(kwargs) + list(extra)
    if out is not None:
        args += ["--out", str(out), "--no-plot", "--quiet"]
    p = subprocess.run(args, capture_output=True, text=True, timeout=240)
    assert p.returncode == 0, p.stderr
    return p.stdout


def manifest(path):
    with open(path) as fh:
        return json.load(fh)
