#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The floors of docs/ARCHITECTURE.md: a module of src/ includes only modules on a lower floor (or itself).

Usage: check_layers.py SOURCE_DIR.  Prints every offending include and exits 1; prints one line per module
and exits 0 when the layering holds.  A folder not named below (a new analysis without its own CMakeLists.txt)
is on floor 4.  The Python binding (python/, outside src/) is on the top floor with cli, and neither includes
the other.
"""
import os
import re
import sys

FLOORS = {"core": 0, "iterate": 1, "reference": 2,
          "bifurcation": 3, "windows": 3, "patterns": 3, "lyapunov": 3, "stats": 3,
          "attractors": 4, "particles": 4, "precision": 4,
          "orbits": 5, "transfer": 5, "extras": 5, "leaves": 5,
          "io": 6, "commands": 7, "cli": 8, "python": 8}
# Folders outside src/ that are modules too.
OUTSIDE = {"python": "python"}
# io depends on core only: results reach it as core::Contents.
ONLY = {"io": {"core"}}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_0-9]+)/')


def main(root):
    src = os.path.join(root, "src")
    bad = []
    summary = []
    dirs = [(m, os.path.join(src, m)) for m in sorted(os.listdir(src))]
    dirs += [(m, os.path.join(root, rel)) for m, rel in OUTSIDE.items()]
    for module, d in dirs:
        if not os.path.isdir(d):
            continue
        floor = FLOORS.get(module, 4)
        used = set()
        for dirpath, subdirs, files in os.walk(d):
            subdirs[:] = [s for s in subdirs if s not in ("tests", "btob")]  # Python files, not C++
            for f in files:
                if not f.endswith((".hpp", ".cpp", ".h", ".in")):
                    continue
                path = os.path.join(dirpath, f)
                with open(path, encoding="utf-8") as fh:
                    for n, line in enumerate(fh, 1):
                        m = INCLUDE.match(line)
                        if not m or m.group(1) == module or m.group(1) == "btob":
                            continue
                        other = m.group(1)
                        if not os.path.isdir(os.path.join(src, other)):
                            continue
                        used.add(other)
                        allowed = ONLY.get(module)
                        if FLOORS.get(other, 4) >= floor or (allowed is not None and other not in allowed):
                            bad.append(f"{os.path.relpath(path, root)}:{n}: {module} (floor {floor}) includes "
                                       f"{other} (floor {FLOORS.get(other, 4)})")
        summary.append(f"{module} (floor {floor}) -> {', '.join(sorted(used)) or 'nothing'}")
    if bad:
        print("layering violated:")
        print("\n".join(bad))
        return 1
    print("\n".join(summary))
    print("layering holds")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
