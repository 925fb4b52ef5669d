# SPDX-License-Identifier: GPL-3.0-or-later
"""Typed references: every Python function's inspect.signature names each keyword of its request (keyword-only, in
the fields' order, then threads, progress and, for a sweep, resume) with a type annotation and the field's default
(none for a required field), and the command line's --help says the same thing about the same field by the other
route (CLI11's option line: the type name, `=default` unless REQUIRED).  The defaults a signature shows are valid:
passing them explicitly gives the result of passing nothing.  The command reference shows no build path."""
import inspect
import re
import subprocess

import btob
import numpy as np
import pytest
from conftest import exe

# Command-line type name -> the Python annotations that field types give (core/field_types.hpp).
CLI_TO_PYTHON = {"INTEGER": {"int"}, "REAL": {"float", "list[float] | str"},
                 "DECIMAL": {"float | str", "list[float | str] | str"}, "TEXT": {"str", "list[str] | str"},
                 None: {"bool"}}
# CLI11's option line: --flag TYPE=default [...] [REQUIRED], then the help after padding (one space at least); a
# list's default holds spaces and is followed by " ...", a scalar's holds none.
OPTION = re.compile(r"^\s+(?:-\w, )?--(?P<flag>[\w-]+)(?: (?P<type>[A-Z]+))?"
                    r"(?:=(?P<default>\S+(?: \S+)*?(?= \.\.\.)|\S*))?(?P<many> \.\.\.)?(?P<required> REQUIRED)?(?:\s|$)")


def help_options(command):
    """{flag: match} of the option lines of `btob COMMAND --help`, run as `btob` (argv[0])."""
    text = subprocess.run(["btob", *command.split(), "--help"], executable=exe(), capture_output=True,
                          text=True).stdout
    return text, {m.group("flag"): m for m in map(OPTION.match, text.splitlines()) if m}


def as_text(value):
    """A Python default back in the command line's text form."""
    if isinstance(value, list):
        return " ".join(as_text(v) for v in value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):  # the shortest round-trip form, as the fields print it ("1", not "1.0")
        text = repr(value)
        return text[:-2] if text.endswith(".0") else text
    return str(value)


@pytest.mark.parametrize("name", btob.FUNCTIONS)
def test_signature_lists_every_field_with_type_and_default(name):
    sig = inspect.signature(getattr(btob, name))
    fields = [k for k, _ in btob._btob._fields[name]]
    extra = ["threads", "progress"] + (["resume"] if btob._btob._signatures[name][1] else [])
    assert list(sig.parameters) == fields + extra
    for p in sig.parameters.values():
        assert p.kind is inspect.Parameter.KEYWORD_ONLY and p.annotation is not inspect.Parameter.empty, p
    doc = getattr(btob, name).__doc__
    for k, annotation, _, required in btob._btob._signatures[name][0]:
        assert f"    {k}: {annotation}" in doc, f"{name}: docstring line of {k}"
        assert (sig.parameters[k].default is inspect.Parameter.empty) == required, k


@pytest.mark.parametrize("name", btob.FUNCTIONS)
def test_command_line_states_the_same_types_and_defaults(name):
    command = btob._btob._commands[name]
    text, options = help_options(command)
    assert not re.search(r"Usage: /", text), text.splitlines()[0]
    sig = inspect.signature(getattr(btob, name))
    seen = 0
    for k, annotation, texts, required in btob._btob._signatures[name][0]:
        m = options.get(k.replace("_", "-"))
        if m is None:
            continue  # a positional field (`btob pattern WORD`): an argument, not an option line
        seen += 1
        assert annotation in CLI_TO_PYTHON[m.group("type")], f"{command} --{m.group('flag')}: {m.group(0)!r}"
        if required:
            assert m.group("required") and m.group("default") is None, f"{command}: {m.group(0)!r}"
        elif annotation != "bool" and texts:
            assert (m.group("default") or "") == " ".join(texts), f"{command}: {m.group(0)!r}"
            assert as_text(sig.parameters[k].default) == " ".join(texts), (k, sig.parameters[k].default)
    assert seen >= 1
    assert " TEXT=0 REQUIRED" not in text


def same(a, b):
    assert sorted(a.arrays) == sorted(b.arrays)
    for key in a.arrays:
        np.testing.assert_array_equal(getattr(a, key), getattr(b, key))


@pytest.mark.parametrize("name, required", [("windows_poly", {"n": "2..3"}), ("pattern_curves", {"word": "132312"})])
def test_the_signatures_defaults_are_the_requests_defaults(name, required):
    fn = getattr(btob, name)
    explicit = {k: p.default for k, p in inspect.signature(fn).parameters.items()
                if p.default is not inspect.Parameter.empty and k not in ("progress", "resume")}
    explicit.update(required)
    same(fn(**required), fn(**explicit))


def test_help_shows_the_signature():
    sig = str(inspect.signature(btob.bifurcation))
    assert sig.startswith("(*, ") and "r_min: 'float | str' = 0.0717" in sig, sig
    assert "threads: 'int' = 0" in sig


def subcommands(words=()):
    """The commands under `btob WORDS`, each as its words joined by spaces: those whose --help has options of a
    request (--threads); a parent that only groups its subcommands (`windows`) is listed through its children, and
    `pattern` is both a command and the parent of `pattern atlas`."""
    text = subprocess.run(["btob", *words, "--help"], executable=exe(), capture_output=True, text=True).stdout
    out = [" ".join(words)] if words and "--threads" in text else []
    if "Subcommands:" not in text:
        return out
    names = [line.split()[0] for line in text.split("Subcommands:", 1)[1].splitlines()
             if line.startswith("  ") and not line.startswith("   ")]
    for n in names:
        out += subcommands((*words, n))
    return out


def test_every_command_of_the_command_line_is_a_python_function():
    """One declaration per command (src/commands/commands.hpp): the command line's request commands and Python's
    functions are the same set (the command line's own: explore, cite and run, are not requests)."""
    cli = set(subcommands()) - {"explore", "cite", "run"}
    assert cli == set(btob._btob._commands.values())
    assert list(btob._btob._commands) == btob.FUNCTIONS
