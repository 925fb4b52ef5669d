#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds btob's documentation site (the CMake target `docs`, and the CTest test docs_build).

Usage: build.py --btob BUILD/btob --pythonpath BUILD/python --out BUILD/docs [--source REPO]

Stages docs/ into OUT/source with what is generated or lives elsewhere in the repository (the command reference from
`btob <sub> --help`, the C++ reference from the headers `cmake --install` installs (gen_cpp.py), the performance page from results/benchmarks, the notebooks of analyses/notebooks, CHANGELOG.md,
a link to results/ for the figures), runs sphinx-build with warnings as errors (-W --keep-going; the notebooks are
executed by nbsphinx), then checks every internal link and image of the HTML (check_links.py).  Exit status 0 only
when all of it succeeds."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen_cli  # noqa: E402
import gen_cpp  # noqa: E402
import gen_csv  # noqa: E402
import gen_paper  # noqa: E402
import gen_performance  # noqa: E402
import gen_python  # noqa: E402
import check_links  # noqa: E402


def stage(repo, src):
    """OUT/source: docs/ (but tools/), the notebooks, CHANGELOG.md and a link to results/ (images only)."""
    if os.path.isdir(src):
        shutil.rmtree(src)
    shutil.copytree(os.path.join(repo, "docs"), src, ignore=shutil.ignore_patterns("tools", "__pycache__"))
    os.makedirs(os.path.join(src, "tutorials"), exist_ok=True)
    nb_dir = os.path.join(repo, "analyses", "notebooks")
    for nb in sorted(os.listdir(nb_dir)):
        if nb.endswith(".ipynb"):
            shutil.copy(os.path.join(nb_dir, nb), os.path.join(src, "tutorials", nb))
    shutil.copy(os.path.join(repo, "CHANGELOG.md"), os.path.join(src, "CHANGELOG.md"))
    # The C++ reference shows examples/cpp (the program the test install_cpp builds against the installed package).
    shutil.copytree(os.path.join(repo, "examples", "cpp"), os.path.join(src, "examples", "cpp"))
    os.symlink(os.path.join(repo, "results"), os.path.join(src, "results"))
    gallery(os.path.join(repo, "results", "README.md"), os.path.join(src, "gallery.md"))


def gallery(readme, out):
    """results/README.md (analyses/gallery.py) as a page: its <img src=X> become Markdown images of results/X, so
    that Sphinx copies them and the link checker sees them."""
    text = re.sub(r'<img src="([^"]+)"[^>]*>', lambda m: f"![{m.group(1)}](results/{m.group(1)})",
                  open(readme).read())
    with open(out, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--btob", required=True, help="the built btob executable")
    ap.add_argument("--pythonpath", required=True, help="the folder holding the built package btob")
    ap.add_argument("--out", required=True, help="output folder (source/ and html/ are made in it)")
    ap.add_argument("--source", default=os.path.dirname(os.path.dirname(HERE)), help="repository root")
    ap.add_argument("--sphinx", default="/usr/bin/python3", help="Python with Sphinx, MyST, nbsphinx and furo")
    a = ap.parse_args()
    repo, out = os.path.abspath(a.source), os.path.abspath(a.out)
    src, html = os.path.join(out, "source"), os.path.join(out, "html")
    t0 = time.monotonic()
    stage(repo, src)
    gen_cli.write(a.btob, os.path.join(src, "reference", "cli.md"))
    gen_performance.write(os.path.join(repo, "results", "benchmarks"), os.path.join(src, "performance_data.md"))
    gen_paper.write(repo, os.path.join(src, "paper_tables.md"))
    gen_csv.write(repo, os.path.join(src, "reference", "csv"))
    # The C++ reference: the headers installed from the executable's build folder, read by Doxygen.
    t_cpp = time.monotonic()
    xml_dir, cpp_pages, undocumented = gen_cpp.write(os.path.dirname(os.path.abspath(a.btob)), os.path.join(out, "cpp"),
                                                     os.path.join(src, "reference", "cpp"))
    print(f"docs: C++ reference, {len(cpp_pages)} headers, {time.monotonic() - t_cpp:.1f} s")
    # A request's field always has documentation (its comment, else its flag's help): one without fails the build.
    # The fields of results and of the parts of sweeps are counted (each should have a comment in its header).
    missing = [m for m in undocumented if re.search(r"Request::", m)]
    print(f"docs: C++ reference, {len(undocumented) - len(missing)} result or part fields without a comment")
    if missing:
        print("docs: request fields without documentation (a comment in the header, or the help of its flag):\n  "
              + "\n  ".join(missing))
        return 1
    env = dict(os.environ, PYTHONPATH=os.path.abspath(a.pythonpath) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               BTOB_EXE=os.path.abspath(a.btob), PYDEVD_DISABLE_FILE_VALIDATION="1", BTOB_DOXYGEN_XML=xml_dir)
    env.pop("MPLBACKEND", None)  # the notebooks' kernels draw inline (their figures go into the pages)
    gen_python.write(a.sphinx, env, os.path.join(src, "reference"))
    if os.path.isdir(html):
        shutil.rmtree(html)
    cmd = [a.sphinx, "-m", "sphinx", "-b", "html", "-W", "--keep-going", "-q", "-E",
           "-d", os.path.join(out, "doctrees"), src, html]
    rc = subprocess.call(cmd, env=env)
    print(f"docs: sphinx-build exit {rc} after {time.monotonic() - t0:.1f} s")
    if rc != 0:
        return 1
    problems = check_links.check(html)
    for p in problems:
        print("docs: broken", p)
    print(f"docs: {len(problems)} broken internal links or images; site in {html}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
