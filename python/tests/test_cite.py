# SPDX-License-Identifier: GPL-3.0-or-later
"""How to cite btob: CITATION.cff is `btob cite --format cff` without its commit line (one record, so the file cannot
drift from the command), its version is CMakeLists.txt's one version, the BibTeX and text name this build's version
and commit (`btob --version`), and btob.cite() prints what the command prints.  A bad format is one line naming the
field and the accepted values, exit 2 (ValueError in Python)."""
import os
import re
import subprocess

import btob
import pytest
from conftest import ROOT, exe


def run(*args):
    return subprocess.run([exe(), *args], capture_output=True, text=True)


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(btob\s+VERSION\s+([0-9.]+)", f.read()).group(1)


def build_commit():
    """The commit `btob --version` reports: 'btob X.Y.Z (COMMIT)'."""
    return re.fullmatch(r"btob \S+ \((\S+)\)\n", run("--version").stdout).group(1)


def test_citation_cff_is_the_commands_record_and_has_the_one_version():
    with open(os.path.join(ROOT, "CITATION.cff"), encoding="utf-8") as f:
        committed = f.read()
    printed = run("cite", "--format", "cff")
    assert printed.returncode == 0, printed.stderr
    commit_lines = [line for line in printed.stdout.splitlines() if line.startswith("commit:")]
    assert commit_lines and commit_lines[0].startswith(f'commit: "{build_commit()}"'), commit_lines
    without_commit = "".join(line for line in printed.stdout.splitlines(keepends=True) if not line.startswith("commit:"))
    assert committed == without_commit, "CITATION.cff differs from `btob cite --format cff`: regenerate it with\n" \
        "  btob cite --format cff | grep -v '^commit:' > CITATION.cff"
    versions = re.findall(r'^version: "([^"]+)"$', committed, re.M)
    assert versions == [project_version()], f"CITATION.cff version {versions}, CMakeLists.txt {project_version()}"
    assert re.search(r"^license: GPL-3\.0-or-later$", committed, re.M)
    assert "Four collapsing one-dimensional particles" in committed.split("references:")[1]


def test_citation_cff_is_yaml_with_the_required_keys():
    yaml = pytest.importorskip("yaml")
    with open(os.path.join(ROOT, "CITATION.cff"), encoding="utf-8") as f:
        d = yaml.safe_load(f)
    assert d["cff-version"] == "1.2.0"
    for key in ("message", "title", "authors", "version", "license", "references"):
        assert d[key], key  # CFF 1.2.0 requires cff-version, message, title, authors
    paper = d["references"][0]
    assert [a["family-names"] for a in paper["authors"]] == ["Castorrini", "Dolmaire"]


def test_bibtex_names_this_build_and_the_paper():
    out = run("cite")  # the default format
    assert out.returncode == 0 and out.stdout == run("cite", "--format", "bibtex").stdout
    bib = out.stdout
    assert bib.count("{") == bib.count("}"), "unbalanced braces"
    entries = re.findall(r"^@(\w+)\{(\w+),$", bib, re.M)
    assert entries == [("software", "btob"), ("misc", "castorrini_dolmaire")]
    assert f"version = {{{project_version()}}}," in bib
    assert f"git commit {build_commit()}" in bib
    assert "author = {Castorrini, Roberto and Dolmaire, Th{\\'e}ophile}," in bib
    assert "title = {Four collapsing one-dimensional particles: a dynamical system approach of the spherical " \
           "billiard reduction}," in bib


def test_text_names_version_commit_and_paper():
    text = run("cite", "--format", "text").stdout
    assert f"version {project_version()} (git commit {build_commit()}" in text
    assert 'R. Castorrini and T. Dolmaire, "Four collapsing' in text


def test_bad_format_is_one_line_exit_2():
    out = run("cite", "--format", "xml")
    assert out.returncode == 2 and out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1 and "--format" in out.stderr and "bibtex" in out.stderr, out.stderr


def test_python_cite_prints_what_the_command_prints():
    for fmt in ("bibtex", "cff", "text"):
        assert btob.cite(fmt) == run("cite", "--format", fmt).stdout, fmt
    assert btob.cite() == btob.cite("bibtex")
    with pytest.raises(ValueError, match="format: got 'xml', expected one of bibtex, cff, text"):
        btob.cite("xml")
