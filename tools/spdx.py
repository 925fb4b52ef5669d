#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Adds the line `SPDX-License-Identifier: GPL-3.0-or-later` to every tracked source file of btob (LICENSE,
docs/licence.md), or with --check lists the files that lack it (exit 1) and changes nothing.

Usage: tools/spdx.py [--check] [--root REPO]

A source file is a file `git ls-files` lists whose name ends in one of SYNTAX's suffixes (C++, Python, shell, CMake,
TOML scene files, the explorer's JavaScript, HTML and CSS, Octave) or is named CMakeLists.txt; never a data file
(CSV, JSON, HDF5, images, notebooks, Markdown), nothing under results/ (computed files, their bytes are recorded in
manifests) and not LICENSE.  The line goes first, in the file's comment syntax, except after what must stay first:
a shebang `#!` (and a Python encoding cookie right after it, PEP 263 allows it only on line 1 or 2), an HTML
`<!DOCTYPE ...>`, a CSS `@charset`.  Idempotent: a file that already has an SPDX-License-Identifier line among its
first lines is left alone (a different identifier there is reported, never rewritten)."""
import argparse
import os
import re
import subprocess
import sys

LICENSE = "GPL-3.0-or-later"
TAG = "SPDX-License-Identifier:"
# suffix -> (comment opener, closer); the longest matching suffix wins (".hpp.in" before ".in").
SYNTAX = {
    ".cpp": ("//", ""), ".hpp": ("//", ""), ".h": ("//", ""), ".hpp.in": ("//", ""), ".js": ("//", ""),
    ".py": ("#", ""), ".sh": ("#", ""), ".slurm": ("#", ""), ".cmake": ("#", ""), ".cmake.in": ("#", ""),
    ".pc.in": ("#", ""), ".toml": ("#", ""), ".m": ("%", ""),
    ".css": ("/*", " */"), ".html": ("<!--", " -->"),
}
NAMES = {"CMakeLists.txt": ("#", "")}
EXCLUDED_DIRS = ("results/",)
HEAD = 5  # an existing identifier is looked for in this many first lines
KEEP_FIRST = re.compile(r"^(#!|<!DOCTYPE|@charset)", re.IGNORECASE)
CODING = re.compile(r"^[ \t\f]*#.*?coding[:=]")  # PEP 263


def syntax(path):
    """The comment syntax of a tracked path, or None when it is not a source file."""
    if path.startswith(EXCLUDED_DIRS) or os.path.basename(path) == "LICENSE":
        return None
    if os.path.basename(path) in NAMES:
        return NAMES[os.path.basename(path)]
    for suffix in sorted(SYNTAX, key=len, reverse=True):
        if path.endswith(suffix):
            return SYNTAX[suffix]
    return None


def insert_at(lines):
    """Index of the line the identifier goes before: after a shebang/doctype/@charset and an encoding cookie."""
    i = 0
    if lines and KEEP_FIRST.match(lines[0]):
        i = 1
    if i < len(lines) and i < 2 and CODING.match(lines[i]):
        i += 1
    return i


def existing(lines):
    """The identifier already stated in the first lines, or None."""
    for line in lines[:HEAD]:
        m = re.search(re.escape(TAG) + r"\s*(\S+)", line)  # the closer is written after a space
        if m:
            return m.group(1)
    return None


def tagged(text, comment):
    """text with the identifier line added (text unchanged when it has one)."""
    lines = text.splitlines(keepends=True)
    if existing(lines) is not None:
        return text
    eol = "\r\n" if lines and lines[0].endswith("\r\n") else "\n"
    opener, closer = comment
    i = insert_at(lines)
    if i == len(lines) and lines and not lines[-1].endswith("\n"):
        lines[-1] += eol
    lines.insert(i, f"{opener} {TAG} {LICENSE}{closer}{eol}")
    return "".join(lines)


def tracked(root):
    out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True).stdout
    return [p for p in out.decode().split("\0") if p]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="list the files without the line; exit 1 if any")
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                    help="the repository (default: this script's)")
    a = ap.parse_args()
    missing, wrong, changed, seen = [], [], 0, 0
    for path in tracked(a.root):
        comment = syntax(path)
        full = os.path.join(a.root, path)
        if comment is None or os.path.islink(full) or not os.path.isfile(full):
            continue
        seen += 1
        with open(full, encoding="utf-8", newline="") as f:
            text = f.read()
        found = existing(text.splitlines())
        if found is not None and found != LICENSE:
            wrong.append(f"{path}: {TAG} {found}, not {LICENSE}")
        elif found is None and a.check:
            missing.append(path)
        elif found is None:
            with open(full, "w", encoding="utf-8", newline="") as f:
                f.write(tagged(text, comment))
            changed += 1
    for line in wrong:
        print(f"spdx: {line}", file=sys.stderr)
    if a.check:
        for path in missing:
            print(f"spdx: no '{TAG} {LICENSE}' line: {path}", file=sys.stderr)
        print(f"spdx: {seen - len(missing) - len(wrong)} of {seen} source files carry {LICENSE}")
        return 1 if missing or wrong else 0
    print(f"spdx: added the line to {changed} of {seen} source files")
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())
