#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The C++ API reference: the headers `cmake --install` puts under <prefix>/include/btob, read by Doxygen (XML only,
the house-style `//` comments marked as documentation by doxygen_filter.py), one Sphinx page per header of the
umbrella header <btob/btob.hpp> made of Breathe directives (Breathe renders Doxygen's XML in Sphinx's C++ domain,
so the pages have the site's theme, search and cross-references).

A page shows the header's own head comment, each struct it declares (a request with its fields and their defaults,
a result with its fields), the results its functions return that other headers declare, and its functions
(run, run_part, merge, work).  write() also lists the public fields of those structs that have no documentation:
build.py fails on a request's (the reference promises every request field) and counts the others."""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import doxygen_filter  # noqa: E402
DOXYFILE = """
PROJECT_NAME = btob
INPUT = {include}
FILE_PATTERNS = *.hpp
RECURSIVE = YES
FULL_PATH_NAMES = YES
STRIP_FROM_PATH = {include}
STRIP_FROM_INC_PATH = {include}
EXTRACT_ALL = YES
EXTRACT_STATIC = YES
EXTRACT_PRIVATE = NO
HIDE_UNDOC_CLASSES = NO
ENABLE_PREPROCESSING = YES
MACRO_EXPANSION = NO
BUILTIN_STL_SUPPORT = YES
GENERATE_HTML = NO
GENERATE_LATEX = NO
GENERATE_XML = YES
XML_PROGRAMLISTING = NO
OUTPUT_DIRECTORY = {out}
XML_OUTPUT = xml
QUIET = YES
WARNINGS = NO
WARN_IF_UNDOCUMENTED = NO
WARN_IF_DOC_ERROR = NO
CASE_SENSE_NAMES = YES
DISTRIBUTE_GROUP_DOC = YES
"""


def install_headers(build, prefix):
    """`cmake --install BUILD --component Unspecified --prefix PREFIX`: the rules without a component (the command,
    the headers, the libraries, the CMake package; not the Python package).  Returns PREFIX/include/btob."""
    if os.path.isdir(prefix):
        shutil.rmtree(prefix)
    subprocess.run(["cmake", "--install", build, "--component", "Unspecified", "--prefix", prefix], check=True,
                   stdout=subprocess.DEVNULL)
    return os.path.join(prefix, "include", "btob")


def run_doxygen(include, out):
    """Doxygen's XML of every installed header in OUT/xml.  The headers are filtered first (doxygen_filter, in this
    process: Doxygen's INPUT_FILTER would start a Python per header) into OUT/include, which Doxygen reads."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    filtered = os.path.join(out, "include")
    for dirpath, _, names in os.walk(include):
        for n in names:
            if n.endswith(".hpp"):
                src = os.path.join(dirpath, n)
                dst = os.path.join(filtered, os.path.relpath(src, include))
                os.makedirs(os.path.dirname(dst), exist_ok=True)
                with open(dst, "w") as f:
                    f.write("\n".join(doxygen_filter.filter_lines(open(src).read().split("\n"))))
    subprocess.run(["doxygen", "-"], input=DOXYFILE.format(include=filtered, out=out), text=True, check=True, cwd=out)
    return os.path.join(out, "xml")


def umbrella_headers(include):
    """The headers <btob/btob.hpp> includes, in its order (module/file.hpp)."""
    text = open(os.path.join(include, "btob.hpp")).read()
    return re.findall(r'^#include "([^"]+)"', text, re.M)


def text_of(node):
    return "".join(node.itertext()).strip() if node is not None else ""


class Xml:
    """Doxygen's XML: the compounds by id, the files by their path under include/btob."""

    def __init__(self, xml_dir):
        self.dir = xml_dir
        self.index = ET.parse(os.path.join(xml_dir, "index.xml")).getroot()
        self.cache = {}
        self.files = {}
        for c in self.index.findall("compound"):
            if c.get("kind") == "file":
                loc = self.compound(c.get("refid")).find("location")
                self.files[loc.get("file")] = c.get("refid")  # relative to include/btob

    def is_class(self, name):
        """Whether a qualified name is a struct or a class (not a namespace)."""
        return any(c.get("kind") in ("struct", "class") and c.findtext("name") == name
                   for c in self.index.findall("compound"))

    def compound(self, refid):
        if refid not in self.cache:
            self.cache[refid] = ET.parse(os.path.join(self.dir, refid + ".xml")).getroot().find("compounddef")
        return self.cache[refid]


def structs_of_file(xml, refid):
    """The structs a file declares (qualified names and ids), in the file's order."""
    fdef = xml.compound(refid)
    found = []
    for ic in fdef.findall("innerclass"):
        c = xml.compound(ic.get("refid"))
        # A struct nested in another is shown inside it (Breathe renders a struct's inner structs).
        nested = xml.is_class(ic.text.rsplit("::", 1)[0])
        if c.get("kind") in ("struct", "class") and c.get("prot") == "public" and not nested:
            line = int(c.find("location").get("line", "0"))
            found.append((line, ic.text, ic.get("refid")))
    return [(name, rid) for _, name, rid in sorted(found)]


def functions_of_file(xml, header):
    """The functions a header declares (Doxygen lists them under their namespace, with the declaring file), in
    the file's order; templates left out (Breathe cannot name one overload of a template)."""
    found = []
    for c in xml.index.findall("compound"):
        if c.get("kind") != "namespace":
            continue
        for m in xml.compound(c.get("refid")).iter("memberdef"):
            loc = m.find("location")
            if m.get("kind") == "function" and loc.get("declfile", loc.get("file")) == header \
                    and m.find("templateparamlist") is None:
                found.append((int(loc.get("declline", loc.get("line"))), m))
    return [m for _, m in sorted(found, key=lambda x: x[0])]


def signature(m):
    """A function as Breathe's doxygenfunction names one overload: qualified name and parameter types."""
    types = ["".join(p.find("type").itertext()).strip() for p in m.findall("param")]
    return f"{m.findtext('qualifiedname')}({', '.join(types)})"


def returned_structs(xml, functions):
    """The structs the functions return (through a reference in the return type): qualified names, ids."""
    out = {}
    for m in functions:
        if m.get("kind") == "function":
            for ref in m.find("type").iter("ref"):
                if ref.get("kindref") == "compound":
                    c = xml.compound(ref.get("refid"))
                    if c.get("kind") in ("struct", "class"):
                        out[text_of(c.find("compoundname"))] = ref.get("refid")
    return out


def undocumented_fields(xml, name, refid):
    """The public data members of a struct with neither a brief nor a detailed description."""
    missing = []
    for sec in xml.compound(refid).findall("sectiondef"):
        if sec.get("kind") not in ("public-attrib", "public-static-attrib"):
            continue
        for m in sec.findall("memberdef"):
            if not text_of(m.find("briefdescription")) and not text_of(m.find("detaileddescription")):
                missing.append(f"{name}::{m.find('name').text}")
    return missing


def head_comment(path):
    """The header's own comment: its first run of // lines after the SPDX line, as a paragraph."""
    lines = []
    for line in open(path).read().split("\n"):
        if line.startswith("// SPDX"):
            continue
        if not line.startswith("//"):
            break
        lines.append(line[2:].strip())
    return " ".join(lines)


def struct_directive(name):
    return f"```{{doxygenstruct}} {name}\n:members:\n:undoc-members:\n```\n"


def page(header, include, structs, others, functions, title):
    """One header's page (MyST Markdown of Breathe directives)."""
    out = [f"# {title}\n", f"`#include <btob/btob.hpp>` (declared in `<btob/{header}>`)\n",
           head_comment(os.path.join(include, header)).replace("*", r"\*") + "\n"]
    out.append("## Requests and results\n")
    out += [struct_directive(n) for n, _ in structs]
    if others:
        out.append("## Types they return, declared in other headers\n")
        out += [struct_directive(n) for n in others]
    if functions:
        out.append("## Functions\n")
        out += [f"```{{doxygenfunction}} {signature(m)}\n```\n" for m in functions]
    return "\n".join(out)


def write(build, work, out_dir):
    """Installs the headers under WORK/prefix, runs Doxygen into WORK/doxygen, writes OUT_DIR/<module>_<file>.md
    per umbrella header; returns (the XML folder for Breathe, the pages' names, undocumented fields)."""
    include = install_headers(build, os.path.join(work, "prefix"))
    xml_dir = run_doxygen(include, os.path.join(work, "doxygen"))
    xml = Xml(xml_dir)
    os.makedirs(out_dir, exist_ok=True)
    pages, missing, shown = [], [], set()
    headers = [h for h in umbrella_headers(include) if h != "core/version.hpp"]
    per_header = {h: structs_of_file(xml, xml.files[h]) for h in headers}
    for structs in per_header.values():
        shown.update(n for n, _ in structs)
    for h in headers:
        structs, functions = per_header[h], functions_of_file(xml, h)
        others = {n: r for n, r in returned_structs(xml, functions).items() if n not in shown}
        shown.update(others)
        for n, r in structs + sorted(others.items()):
            missing += undocumented_fields(xml, n, r)
        name = h.replace("/", "_").replace(".hpp", "")
        with open(os.path.join(out_dir, name + ".md"), "w") as f:
            f.write(page(h, include, structs, sorted(others), functions, f"`{h}`"))
        pages.append(name)
    return xml_dir, pages, missing


if __name__ == "__main__":
    xml_dir, pages, missing = write(sys.argv[1], sys.argv[2], sys.argv[3])
    print(xml_dir, pages)
    print(len(missing), "undocumented fields")
    print("\n".join(missing))
