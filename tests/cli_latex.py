#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Tables for papers: `--format latex` gives the CSV's table as a booktabs LaTeX table, digit for digit.

Runs the commands whose tables a paper quotes, each with --format latex on standard output and again with --out
(NAME.csv, NAME.tex, NAME.h5): window bounds (Table B.1, with certificates), a pattern's stability window, an
orbit's exponents and a classification (values with error bars), and basin fractions with their intervals.  Each
table must
  - have the booktabs rules \\toprule, \\midrule, \\bottomrule once each, in that order, and as many cells in every
    row (header included) as its column specification has columns;
  - carry no unescaped LaTeX special character (& % $ # _ { } ~ ^ outside the markup the writer emits);
  - hold the CSV's cells in order: every number with the CSV's digits (mantissa and exponent), every text cell
    escaped back to the CSV's text, nothing dropped or added (an empty cell prints as --);
  - print each exact decimal as NAME.h5 stores it (lower_bound_decimal, upper_bound_decimal, r_low_decimal);
  - explain each status marker under the table (certified / estimated / conjectured with its basis);
  - compile with pdflatex when a TeX engine is installed (skipped otherwise: the structure above is then the check);
and the stdout table must equal NAME.tex.  `--format html` must fail with exit 2 and one line naming the field.

Usage: cli_latex.py PATH/TO/btob   exit 0 when every check passes, 1 otherwise (each failure printed).
"""
import csv
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def run(btob, args):
    p = subprocess.run([btob, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(f"btob {' '.join(args)} exited {p.returncode}: {p.stderr.strip()[-300:]}")
    return p.stdout


NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
MATH_NUMBER = re.compile(r"([+-]?(?:\d+\.?\d*|\.\d+))(?:\\times 10\^\{(-?\d+)\})?")
UNESCAPE = [("\\textbackslash{}", "\\"), ("\\textasciitilde{}", "~"), ("\\textasciicircum{}", "^"), ("\\&", "&"),
            ("\\%", "%"), ("\\$", "$"), ("\\#", "#"), ("\\_", "_"), ("\\{", "{"), ("\\}", "}")]


def csv_tokens(cells):
    """The CSV row's cells as tokens: ('n', mantissa, exponent) for a number, ('t', text) otherwise; '' skipped."""
    out = []
    for c in cells:
        m = NUMBER.match(c)
        if c == "":
            continue
        if m:
            mant, _, exp = c.partition("e") if "e" in c else c.partition("E")
            out.append(("n", mant, int(exp) if exp else None))
        else:
            out.append(("t", c))
    return out


def latex_tokens(cells):
    """The LaTeX row's cells as the same tokens: math numbers ($...$, v \\pm e, [a, b]) and unescaped text."""
    out = []
    for c in cells:
        if c == "--":
            continue
        if "$" in c:
            for piece in re.findall(r"\$([^$]*)\$", c):
                for mant, exp in MATH_NUMBER.findall(piece):
                    out.append(("n", mant, int(exp) if exp else None))
        else:
            for a, b in UNESCAPE:
                c = c.replace(a, b)
            out.append(("t", c))
    return out


def table_parts(tex, where):
    """(column spec, header cells, rows of cells, notes text) of the one tabular in `tex`."""
    spec = re.search(r"\\begin\{tabular\}\{([lrc]+)\}", tex)
    if not spec:
        fail(f"{where}: no \\begin{{tabular}}{{...}}")
        return None
    pos = [tex.find(rule) for rule in ("\\toprule", "\\midrule", "\\bottomrule")]
    if any(p < 0 for p in pos) or pos != sorted(pos) or any(tex.count(r) != 1 for r in
                                                            ("\\toprule", "\\midrule", "\\bottomrule")):
        fail(f"{where}: booktabs rules missing, repeated or out of order: {pos}")
        return None
    header = tex[pos[0] + len("\\toprule"):pos[1]].strip()
    body = tex[pos[1] + len("\\midrule"):pos[2]].strip()
    lines = [header] + [l for l in body.split("\n") if l.strip()]
    rows = []
    for l in lines:
        if not l.endswith(" \\\\"):
            fail(f"{where}: a row does not end in \\\\: {l[:80]}")
            return None
        rows.append(l[:-3].split(" & "))
    ncol = len(spec.group(1))
    for r in rows:
        if len(r) != ncol:
            fail(f"{where}: a row has {len(r)} cells, the column specification {ncol}: {' & '.join(r)[:100]}")
    notes = tex[pos[2]:tex.find("\\caption")]
    return spec.group(1), rows[0], rows[1:], notes


def check_escaped(cells, where):
    for c in cells:
        text = re.sub(r"\$[^$]*\$", "", c)  # math is the writer's own markup
        text = re.sub(r"\\(textbackslash|textasciitilde|textasciicircum|textsuperscript)\{[^}]*\}|\\[&%$#_{}]", "", text)
        if re.search(r"[&%$#_{}~^\\]", text):
            fail(f"{where}: unescaped special character in cell {c!r}")


def check_table(tex, csv_text, where):
    """Structure, escaping and the CSV's cells, row by row; returns (header, rows) or None."""
    parts = table_parts(tex, where)
    if parts is None:
        return None
    spec, header, rows, notes = parts
    csv_rows = list(csv.reader(io.StringIO(csv_text)))
    if len(rows) != len(csv_rows) - 1:
        fail(f"{where}: {len(rows)} rows, the CSV {len(csv_rows) - 1}")
        return None
    for i, (lr, cr) in enumerate(zip(rows, csv_rows[1:])):
        check_escaped(lr, where)
        if latex_tokens(lr) != csv_tokens(cr):
            fail(f"{where}: row {i + 1} differs from the CSV: {latex_tokens(lr)} vs {csv_tokens(cr)}")
    for marker in set(re.findall(r"\\textsuperscript\{(\w)\}", " & ".join(header))):
        if not re.search(r"\\textsuperscript\{" + marker + r"\}\\,(certified|estimated|conjectured)", notes):
            fail(f"{where}: header marker {marker} has no status note under the table")
    return header, rows, notes


def column(header, rows, name):
    """The cells of the column whose header starts with `name` (escaped, before its marker); for P_low or P_high,
    the low or high end of the interval column P [low, high]."""
    esc = name.replace("_", "\\_")
    for j, h in enumerate(header):
        if h == esc or h.startswith(esc + "\\textsuperscript"):
            return [r[j] for r in rows]
    for end, k in (("_low", 0), ("_high", 1)):
        prefix = esc[:-len(end) - 1] if name.endswith(end) else None
        for j, h in enumerate(header):
            if prefix and h.startswith(prefix) and h.endswith(" [low, high]"):
                return [re.findall(r"\$[^$]*\$", r[j])[k] if r[j].startswith("[") else r[j] for r in rows]
    fail(f"no column {name} in {header}")
    return []


def check_decimals(cells, h5path, dataset, where):
    """Each cell's number ($0.171572875254$) is the decimal NAME.h5 stores, character for character."""
    with h5py.File(h5path, "r") as f:
        stored = [s.decode() if isinstance(s, bytes) else str(s) for s in f[dataset][()]]
    shown = [c.strip("$") if c != "--" else "" for c in cells]
    if shown != stored:
        fail(f"{where}: {dataset} printed {shown[:4]}..., NAME.h5 stores {stored[:4]}...")


def compile_if_possible(tex, tmp, where):
    engine = shutil.which("pdflatex")
    if not engine:
        return False
    doc = "\\documentclass{article}\n\\usepackage{booktabs}\n\\begin{document}\n" + tex + "\\end{document}\n"
    path = os.path.join(tmp, "doc.tex")
    with open(path, "w") as f:
        f.write(doc)
    p = subprocess.run([engine, "-interaction=nonstopmode", "-halt-on-error", "doc.tex"], cwd=tmp,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        fail(f"{where}: pdflatex failed: {p.stdout[-400:]}")
    return True


def without_comments(tex):
    return "\n".join(l for l in tex.splitlines() if not l.startswith("%"))


# (what, arguments, file stem, (column, decimal dataset) pairs, statuses the notes must name)
CASES = [
    ("windows bounds", ["windows", "bounds", "--n", "1..6", "--digits", "12", "--certify"], "bounds",
     [("lower_bound", "lower_bound_decimal"), ("upper_bound", "upper_bound_decimal")], ["certified", "conjectured"]),
    ("pattern --window", ["pattern", "1133", "--window"], "pattern", [("r_low", "r_low_decimal"),
                                                                       ("r_high", "r_high_decimal")], ["estimated"]),
    ("lyapunov", ["lyapunov", "--r", "0.11", "--point", "1,0.3,-0.5", "--iterations", "20000"], "lyapunov", [],
     ["estimated"]),
    ("classify", ["classify", "--r", "0.2", "--point", "1,0.8,-1"], "classify", [], []),
]


def check_stdout_command(btob, tmp, what, args, stem, decimals, statuses):
    printed = run(btob, args + ["--format", "latex"])
    out = os.path.join(tmp, stem)
    run(btob, args + ["--format", "latex", "--out", out, "--name", stem, "--quiet"])
    tex_path, csv_path = os.path.join(out, stem + ".tex"), os.path.join(out, stem + ".csv")
    if not (os.path.exists(tex_path) and os.path.exists(csv_path)):
        fail(f"{what}: --format latex --out wrote no {stem}.tex beside {stem}.csv")
        return
    tex, csv_text = open(tex_path).read(), open(csv_path).read()
    if without_comments(printed) != without_comments(tex):
        fail(f"{what}: the table printed differs from {stem}.tex")
    got = check_table(tex, csv_text, what)
    if got is None:
        return
    header, rows, notes = got
    for col, dataset in decimals:
        check_decimals(column(header, rows, col), os.path.join(out, stem + ".h5"), dataset, what)
    for s in statuses:
        if not re.search(r"\\textsuperscript\{\w\}\\," + s, notes):
            fail(f"{what}: no '{s}' status note under the table")
    compile_if_possible(tex, tmp, what)


def check_basins(btob, tmp):
    """A file command: --format latex writes NAME_fractions.tex beside NAME_fractions.csv (fractions, intervals)."""
    out = os.path.join(tmp, "basins")
    run(btob, ["basins", "--r", "0.2", "--grid", "sphere:24x24", "--replicates", "0", "--out", out, "--name", "b",
               "--no-plot", "--quiet", "--format", "latex"])
    tex_path = os.path.join(out, "b_fractions.tex")
    if not os.path.exists(tex_path):
        fail("basins: --format latex wrote no b_fractions.tex")
        return
    got = check_table(open(tex_path).read(), open(os.path.join(out, "b_fractions.csv")).read(), "basins fractions")
    if got and not any(c.startswith("[$") for r in got[1] for c in r):
        fail("basins: no interval [low, high] in the fractions table")


def check_bad_format(btob):
    p = subprocess.run([btob, "windows", "bounds", "--n", "2", "--format", "html"], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    if p.returncode != 2 or p.stdout or "format" not in p.stderr or len(p.stderr.strip().splitlines()) != 1:
        fail(f"--format html: exit {p.returncode}, stdout {p.stdout[:60]!r}, stderr {p.stderr.strip()!r}")


def main():
    btob = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as tmp:
        for case in CASES:
            check_stdout_command(btob, tmp, *case)
        check_basins(btob, tmp)
    check_bad_format(btob)
    print("pdflatex:", shutil.which("pdflatex") or "not installed (structure checked instead)")
    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    print("ok: every LaTeX table matches its CSV")
    return 0


if __name__ == "__main__":
    sys.exit(main())
