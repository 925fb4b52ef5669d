# SPDX-License-Identifier: GPL-3.0-or-later
"""One spelling per concept: every Python function's keyword arguments (from the binding) and every command's flags
(from `btob CMD --help`) are checked against the vocabulary the README lists.  A second spelling of a concept
(n1 for a grid's size, rs for a list of r, nthreads for threads, ...) fails, naming the function or command."""
import re
import subprocess

import btob
import pytest
from conftest import exe

# The concepts and their one spelling each (README, "The parameter vocabulary").
CONCEPTS = {
    "r": {"r", "r_min", "r_max", "r_count", "r_values"},
    "grid": {"grid", "w1_range"},
    "point": {"point", "points"},
    "precision": {"precision"},
    "seed": {"seed"},
    "threads": {"threads"},
    "iterations": {"iterations"},
    "transient": {"transient"},
}
# Spellings of those concepts that are not the one (the keys a user would otherwise meet beside the right one).
SECOND = {
    "n1": "grid", "n2": "grid", "size": "grid", "w1_min": "grid", "w1_max": "grid", "nx": "grid", "ny": "grid",
    "rs": "r", "r_list": "r", "r_range": "r", "n_r": "r", "r_n": "r", "r_value": "r", "r_lo": "r", "r_hi": "r",
    "x0": "point", "ic": "point", "initial": "point", "start_point": "point", "initial_point": "point",
    "dtype": "precision", "scalar": "precision", "scalar_type": "precision",
    "rng_seed": "seed", "random_seed": "seed",
    "jobs": "threads", "nthreads": "threads", "num_threads": "threads", "n_threads": "threads",
    "iters": "iterations", "n_iterations": "iterations", "steps": "iterations", "n_steps": "iterations",
    "burn_in": "transient", "warmup": "transient", "discard": "transient", "skip": "transient",
}


def offences(where, names, defaults=None):
    bad = []
    for n in names:
        if n in SECOND:
            bad.append(f"{where}: '{n}' is a second spelling of {SECOND[n]} (use one of {sorted(CONCEPTS[SECOND[n]])})")
        elif n.startswith("r_") and n not in CONCEPTS["r"]:
            bad.append(f"{where}: '{n}' spells r otherwise than r / r_min, r_max, r_count / r_values")
    if defaults and len(defaults.get("r", [])) > 1:
        bad.append(f"{where}: 'r' holds several values (a list of r is r_values)")
    return bad


def test_python_keywords_use_one_spelling_per_concept():
    bad = []
    for function, fields in btob._btob._fields.items():
        names = [k for k, _ in fields] + ["threads"]
        bad += offences(f"btob.{function}", names, dict(fields))
    assert not bad, "\n".join(bad)


def subcommands(path):
    """The subcommands listed by `btob PATH --help` (CLI11's 'Subcommands:' block)."""
    text = subprocess.run([exe(), *path, "--help"], capture_output=True, text=True).stdout
    if "Subcommands:" not in text:
        return []
    block = text.split("Subcommands:", 1)[1]
    return [m.group(1) for m in re.finditer(r"^  (\S+)", block, re.M)]


def flags(path):
    text = subprocess.run([exe(), *path, "--help"], capture_output=True, text=True).stdout
    return sorted({m.group(1).replace("-", "_") for m in re.finditer(r"--([a-z0-9][a-z0-9-]*)", text)} - {"help"})


def test_command_flags_use_one_spelling_per_concept():
    bad, seen = [], 0
    stack = [[c] for c in subcommands([])]
    while stack:
        path = stack.pop()
        subs = subcommands(path)
        stack += [path + [s] for s in subs]
        names = flags(path)
        seen += 1
        bad += offences("btob " + " ".join(path), names)
    assert seen >= 20, f"only {seen} commands found in btob --help"
    assert not bad, "\n".join(bad)


def test_the_checks_catch_a_second_spelling():
    assert offences("f", ["n1", "grid"]) and offences("f", ["r_lo"]) and offences("f", ["r"], {"r": ["0.1", "0.2"]})
    assert not offences("f", ["r_min", "r_max", "r_count", "grid", "point", "lyap_iterations"])


def test_the_one_spellings_work_where_the_issue_found_others():
    """basins_r takes an r range like every other sweep; lyapunov_strip takes grid= like basins and hyperbolicity;
    integers take exact scientific notation."""
    res = btob.basins_r(r_min=0.2, r_max=0.3, r_count=2, grid="random:4", transient=300, iterations=300,
                        lyap_iterations=400, lyap_transient=50)
    assert res.r.tolist() == [0.2, 0.3]
    strip = btob.lyapunov_strip(r=0.3, grid="strip:4x3:-1:1", iterations="4e2", transient=50)
    assert strip.lambda1.shape == (4, 3) and strip.w1_cell.tolist()[0] == -0.75
    with pytest.raises(ValueError, match="iterations: got '4.005e2', expected an integer"):
        btob.lyapunov_strip(r=0.3, grid="strip:4x3", iterations="4.005e2", transient=50)
