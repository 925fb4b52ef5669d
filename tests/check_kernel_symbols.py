#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""No function is compiled both for the kernel's instruction set and for the baseline, to be picked by the linker.

Usage: check_kernel_symbols.py BUILD_SRC_DIR.  Only the kernel units (src/*/kernel_*.cpp) are compiled with the kernel
flags (-march=native, ...).  A function defined in a header and emitted out of line (a weak symbol) by a kernel unit
and by another unit is linked once, from either: btob's DensityRecorder::certain_bins<double> was reference.cpp's
baseline SSE2 copy while the benchmark measured the kernel's AVX-512 one (docs/ARCHITECTURE.md, "Determinism").
Reads every libbtob_*.a under BUILD_SRC_DIR with nm, prints every btob function emitted by both kinds of unit outside
the list of harmless ones below, and exits 1 if there is one.
"""
import glob
import os
import re
import subprocess
import sys

# Emitted by both kinds and harmless: no per-lane arithmetic (destructors, type information, argument checks) or
# computed once per run (the branch matrices, for the renormalisation interval).
HARMLESS = [re.compile(p) for p in (r"~", r"^typeinfo", r"^vtable", r"btob::core::validate_", r"btob::core::P[123]?<")]
LINE = re.compile(r"^(?P<lib>[^:]+):(?P<member>[^:]+):\s*[0-9a-f]*\s+(?P<type>\S)\s+(?P<name>.*)$")


def main(build_src):
    libs = sorted(glob.glob(os.path.join(build_src, "*", "libbtob_*.a")))
    if not libs:
        print(f"check_kernel_symbols: no libbtob_*.a under {build_src}")
        return 1
    kernel, other = {}, {}
    for lib in libs:
        out = subprocess.run(["nm", "-C", "--defined-only", "-A", lib], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            m = LINE.match(line)
            if not m or m["type"] != "W" or "btob::" not in m["name"]:
                continue
            units = kernel if os.path.basename(m["member"]).startswith("kernel_") else other
            units.setdefault(m["name"], set()).add(os.path.basename(m["member"]))
    both = sorted(n for n in kernel if n in other and not any(p.search(n) for p in HARMLESS))
    for n in both:
        print(f"{n}\n    kernel units: {', '.join(sorted(kernel[n]))}\n    other units: {', '.join(sorted(other[n]))}")
    print(f"check_kernel_symbols: {len(libs)} libraries, {len(kernel)} weak btob functions in kernel units, "
          f"{len(both)} also emitted by other units")
    return 1 if both else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
