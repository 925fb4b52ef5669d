#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/spdx.py on a scratch git repository holding one file of each kind: the identifier goes first in the file's
comment syntax, after a shebang (and a Python encoding cookie), an HTML doctype, a CSS @charset; data files, results/
and LICENSE are left alone; a second run changes nothing (idempotent); --check fails before the run, passes after,
and fails on a different identifier, which is never rewritten.  Each expectation is written out here by hand, not
computed by the script's own functions.

Usage: spdx_test.py SCRATCH_DIR"""
import os
import shutil
import subprocess
import sys

TOOL = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools", "spdx.py")
ID = "SPDX-License-Identifier: GPL-3.0-or-later"
# path -> (content before, content expected after)
CASES = {
    "src/a.cpp": ("#include <x>\n", f"// {ID}\n#include <x>\n"),
    "src/a.hpp": ("#pragma once\n", f"// {ID}\n#pragma once\n"),
    "cmake/btob.hpp.in": ("// x\n", f"// {ID}\n// x\n"),
    "cmake/btobConfig.cmake.in": ("include(x)\n", f"# {ID}\ninclude(x)\n"),
    "CMakeLists.txt": ("project(x)\n", f"# {ID}\nproject(x)\n"),
    "src/CMakeLists.txt": ("add_library(x)", f"# {ID}\nadd_library(x)"),
    "tools/run.sh": ("#!/usr/bin/env bash\nset -e\n", f"#!/usr/bin/env bash\n# {ID}\nset -e\n"),
    "tools/plain.py": ('"""Doc."""\n', f'# {ID}\n"""Doc."""\n'),
    "tools/coded.py": ("#!/usr/bin/python3\n# -*- coding: utf-8 -*-\nx = 1\n",
                       f"#!/usr/bin/python3\n# -*- coding: utf-8 -*-\n# {ID}\nx = 1\n"),
    "tools/crlf.py": ("x = 1\r\ny = 2\r\n", f"# {ID}\r\nx = 1\r\ny = 2\r\n"),
    "tools/empty.py": ("", f"# {ID}\n"),
    "analyses/scenes/s.toml": ("r = 0.1\n", f"# {ID}\nr = 0.1\n"),
    "analyses/octave/f.m": ("x = 1;\n", f"% {ID}\nx = 1;\n"),
    "web/index.html": ("<!DOCTYPE html>\n<html>\n", f"<!DOCTYPE html>\n<!-- {ID} -->\n<html>\n"),
    "web/app.js": ("'use strict';\n", f"// {ID}\n'use strict';\n"),
    "web/app.css": ('@charset "utf-8";\nbody {}\n', f'@charset "utf-8";\n/* {ID} */\nbody {{}}\n'),
    "web/plain.css": ("body {}\n", f"/* {ID} */\nbody {{}}\n"),
    "tools/tagged.py": (f"# {ID}\nx = 1\n", f"# {ID}\nx = 1\n"),
    # left alone: data, results, the licence text, notebooks, Markdown
    "LICENSE": ("GNU GENERAL PUBLIC LICENSE\n", "GNU GENERAL PUBLIC LICENSE\n"),
    "results/fig/run.py": ("x = 1\n", "x = 1\n"),
    "results/fig/data.csv": ("a,b\n", "a,b\n"),
    "data/t.json": ("{}\n", "{}\n"),
    "docs/page.md": ("# Page\n", "# Page\n"),
    "analyses/n.ipynb": ("{}\n", "{}\n"),
    "notes.txt": ("text\n", "text\n"),
}


def run(root, *args):
    return subprocess.run([sys.executable, TOOL, "--root", root, *args], capture_output=True, text=True)


def write_all(root, which):
    for path, contents in CASES.items():
        os.makedirs(os.path.dirname(os.path.join(root, path)) or root, exist_ok=True)
        with open(os.path.join(root, path), "w", newline="") as f:
            f.write(contents[which])


def read(root, path):
    with open(os.path.join(root, path), newline="") as f:
        return f.read()


def main():
    root = os.path.abspath(sys.argv[1])
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    subprocess.run(["git", "init", "-q", root], check=True)
    write_all(root, 0)
    with open(os.path.join(root, "untracked.py"), "w") as f:
        f.write("x = 1\n")
    subprocess.run(["git", "-C", root, "add", "--", *CASES], check=True)
    failures = []
    r = run(root, "--check")
    if r.returncode != 1 or "src/a.cpp" not in r.stderr or "tools/tagged.py" in r.stderr:
        failures.append(f"--check before: exit {r.returncode}, stderr {r.stderr!r}")
    if any(read(root, p) != c[0] for p, c in CASES.items()):
        failures.append("--check changed a file")
    for attempt in ("first run", "second run (idempotent)"):
        r = run(root)
        if r.returncode != 0:
            failures.append(f"{attempt}: exit {r.returncode}: {r.stderr}")
        for path, (_, expected) in CASES.items():
            if read(root, path) != expected:
                failures.append(f"{attempt}: {path}: {read(root, path)!r}, expected {expected!r}")
    if read(root, "untracked.py") != "x = 1\n":
        failures.append("an untracked file was changed")
    r = run(root, "--check")
    if r.returncode != 0:
        failures.append(f"--check after: exit {r.returncode}, stderr {r.stderr!r}")
    other = "# SPDX-License-Identifier: MIT\nx = 1\n"
    with open(os.path.join(root, "tools/plain.py"), "w") as f:
        f.write(other)
    r = run(root, "--check")
    if r.returncode != 1 or "tools/plain.py: SPDX-License-Identifier: MIT" not in r.stderr:
        failures.append(f"--check on another identifier: exit {r.returncode}, stderr {r.stderr!r}")
    r = run(root)
    if r.returncode != 1 or read(root, "tools/plain.py") != other:
        failures.append(f"a different identifier was rewritten or accepted: exit {r.returncode}")
    for f in failures:
        print("spdx_test:", f)
    print(f"spdx_test: {len(CASES)} files, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
