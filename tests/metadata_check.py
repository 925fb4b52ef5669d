#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The licence is stated the same everywhere: LICENSE is the full text of the GPL, version 3 (byte for byte Debian's
/usr/share/common-licenses/GPL-3 when present, else its first and last lines), setup.py's metadata, the CPack
licence of cmake/Package.cmake and the Debian copyright file (machine-readable DEP-5: Format line, a Files: *
paragraph, a standalone License paragraph for the short name it uses) all say GPL-3.0-or-later.

Usage: metadata_check.py REPO"""
import os
import re
import subprocess
import sys

SPDX = "GPL-3.0-or-later"
failures = []


def fail(msg):
    failures.append(msg)
    print("metadata_check:", msg)


def read(root, path):
    with open(os.path.join(root, path), encoding="utf-8") as f:
        return f.read()


def check_license_text(root):
    text = read(root, "LICENSE")
    debian = "/usr/share/common-licenses/GPL-3"
    if os.path.exists(debian):
        if text != open(debian, encoding="utf-8").read():
            fail(f"LICENSE differs from {debian}")
    elif not (text.lstrip().startswith("GNU GENERAL PUBLIC LICENSE\n                       Version 3, 29 June 2007")
              and "END OF TERMS AND CONDITIONS" in text and len(text) > 30000):
        fail("LICENSE is not the full text of the GPL, version 3")


def check_setup(root):
    """setup.py's license= and classifier, as setuptools reads them (python3 setup.py --license)."""
    r = subprocess.run([sys.executable, "setup.py", "--license", "--classifiers"], cwd=root, capture_output=True,
                       text=True)
    out = r.stdout.splitlines()
    if r.returncode != 0 or SPDX not in out:
        fail(f"setup.py --license: {r.stdout!r} {r.stderr[-300:]!r}")
    if "License :: OSI Approved :: GNU General Public License v3 or later (GPLv3+)" not in out:
        fail("setup.py: no GPLv3+ trove classifier")


def check_cpack(root):
    m = re.search(r'set\(BTOB_LICENSE "([^"]+)"\)', read(root, "cmake/Package.cmake"))
    if not m or m.group(1) != SPDX:
        fail(f"cmake/Package.cmake: BTOB_LICENSE {m.group(1) if m else 'missing'}, not {SPDX}")


def dep5_paragraphs(text):
    """Paragraphs of a DEP-5 file as dicts field -> value (continuation lines joined)."""
    paragraphs = []
    for block in re.split(r"\n\s*\n", text.strip()):
        fields, key = {}, None
        for line in block.splitlines():
            if line[:1] in (" ", "\t") and key:
                fields[key] += "\n" + line.strip()
            elif ":" in line:
                key, value = line.split(":", 1)
                fields[key] = value.strip()
            else:
                fail(f"cmake/debian/copyright: not a DEP-5 field line: {line!r}")
        paragraphs.append(fields)
    return paragraphs


def check_copyright(root):
    paragraphs = dep5_paragraphs(read(root, "cmake/debian/copyright"))
    header = paragraphs[0]
    if header.get("Format") != "https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/":
        fail("cmake/debian/copyright: the first paragraph has no DEP-5 Format line")
    files = [p for p in paragraphs if p.get("Files") == "*"]
    if len(files) != 1 or not files[0].get("Copyright"):
        fail("cmake/debian/copyright: no single 'Files: *' paragraph with a Copyright field")
        return
    short = files[0].get("License", "")
    if short != "GPL-3+":  # Debian's short name of GPL-3.0-or-later
        fail(f"cmake/debian/copyright: Files: * License {short!r}, not GPL-3+")
    standalone = [p for p in paragraphs if set(p) == {"License"} and p["License"].startswith(short + "\n")]
    if not standalone or "/usr/share/common-licenses/GPL-3" not in standalone[0]["License"] \
            or "either version 3 of the License, or" not in standalone[0]["License"].replace("\n", " "):
        fail("cmake/debian/copyright: no License paragraph for GPL-3+ with the notice and the common-licenses path")


def main():
    root = os.path.abspath(sys.argv[1])
    check_license_text(root)
    check_setup(root)
    check_cpack(root)
    check_copyright(root)
    print(f"metadata_check: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
