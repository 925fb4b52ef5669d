#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Doxygen's INPUT_FILTER for btob's headers: reads a header, prints it with its house-style comments marked as
documentation, every line kept in place (Doxygen's line numbers stay right).

The headers document with plain `//` comments, never Doxygen's `///`: a field's comment trails it
(`long iterations = 100000;   // averaged map iterations, >= blocks`), a struct's or a function's comment is the
run of `//` lines just above it.  At namespace or struct level (not inside a function body or an initialiser):
  - a trailing `//` after a declaration ending in `;` or `,` becomes `///<` (documents that member), and so do the
    comment-only lines below it that continue it (their `//` in the same column);
  - a run of comment-only lines directly above a declaration becomes `///` (documents what follows), unless a
    blank line, a preprocessor line or the end of the scope follows it (a note about the section, the file's
    head) or it is a section rule (`// ---- ...`).
Usage: doxygen_filter.py FILE"""
import re
import sys

SCOPE_OPENER = re.compile(r"\b(namespace|struct|class|enum|union)\b")


def split_comment(line):
    """(code, comment column or -1): the `//` that starts a comment, outside string and character literals."""
    i, quote = 0, None
    while i < len(line):
        c = line[i]
        if quote:
            if c == "\\":
                i += 1
            elif c == quote:
                quote = None
        elif c in "\"'":
            if c == "'" and i > 0 and line[i - 1].isalnum():  # a digit separator (1'000), not a character literal
                pass
            else:
                quote = c
        elif line.startswith("//", i):
            return line[:i], i
        i += 1
    return line, -1


def braces(code):
    """The braces of a line of code in order, string literals removed."""
    code = re.sub(r'"(\\.|[^"\\])*"', '""', code)
    return [c for c in code if c in "{}"]


def top_level_split(text, sep=","):
    """text split at the separators outside (), <>, [] and {}."""
    parts, depth, cur = [], 0, ""
    for c in text:
        if c in "(<[{":
            depth += 1
        elif c in ")>]}":
            depth -= 1
        if c == sep and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += c
    return parts + [cur]


MEMBER = re.compile(r"^(?P<type>[\w:<>, \[\]*&]+?)\s+(?P<first>\w+\s*(=.*|\{.*\})?)$")


def declarators(code):
    """A member declaration of several declarators, `T a = 1, b = 2;`, as the declarations ["T a = 1", "T b = 2"];
    None for anything else (one declarator, a function, a statement)."""
    body = code.strip()
    if not body.endswith(";") or body.startswith(("using", "return", "typedef", "friend", "static_assert", "template")):
        return None
    parts = [p.strip() for p in top_level_split(body[:-1])]
    if len(parts) < 2 or "(" in parts[0].split("=")[0] or "{" in parts[0].split("=")[0].rstrip("{"):
        return None
    m = MEMBER.match(parts[0])
    if not m or not all(re.match(r"^\w+\s*(=.*|\{.*\})?$", p) for p in parts[1:]):
        return None
    return [parts[0]] + [f"{m.group('type')} {p}" for p in parts[1:]]


def next_code(lines, i):
    """The first line after a run of comment-only lines starting at i: its index."""
    while i < len(lines) and lines[i].lstrip().startswith("//"):
        i += 1
    return i


def documents(lines, j):
    """Whether a comment run followed by line j documents it: j is a declaration of the same scope."""
    if j >= len(lines):
        return False
    s = lines[j].strip()
    return bool(s) and not s.startswith(("#", "}", "public:", "private:", "protected:"))


FIELD_HELP = re.compile(r'\bv\(\s*"([^"]+)",\s*(\w+),\s*((?:"(?:[^"\\]|\\.)*"\s*)+)')
STRUCT_NAME = re.compile(r"^\s*(?:struct|class)\s+(\w+)", re.M)


def field_helps(text):
    """{(struct, member): help} from the requests' `fields` lists, v("name", member, "help" ...): the text the
    command line's --help and Python's signatures show, used for a member that has no comment of its own."""
    helps = {}
    for m in FIELD_HELP.finditer(text):
        before = text[:m.start()]
        names = STRUCT_NAME.findall(before)
        help_text = "".join(re.findall(r'"((?:[^"\\]|\\.)*)"', m.group(3))).replace('\\"', '"')
        helps[(names[-1] if names else None, m.group(2))] = help_text
    return helps


def is_member(code):
    """A data member's declaration (one or several declarators), not a function, a statement or a type."""
    body = code.strip()
    if not body.endswith(";") or body.startswith(("using", "return", "typedef", "friend", "static_assert",
                                                   "template", "struct", "class", "enum", "}", "#")):
        return False
    head = re.split(r"[={]", body[:-1], 1)[0]
    return "(" not in head and "operator" not in head and bool(re.search(r"[\w>*&]\s+\**&?\w+\s*(\[.*\])?$",
                                                                         head.strip().split(",")[0].strip()))


def member_run(lines, j):
    """How many member declarations follow from line j, consecutive (no blank or comment-only line between)."""
    k = j
    while k < len(lines) and is_member(split_comment(lines[k])[0]):
        k += 1
    return k - j


class Filter:
    """One header: the lines it has read, the braces open, the struct each scope brace opened."""

    def __init__(self, lines):
        self.lines, self.out = lines, []
        self.helps = field_helps("\n".join(lines))
        self.stack, self.names, self.pending = [], [], ""
        self.trailing_col, self.group_end, self.commented = -1, -1, -1

    def at_scope(self):
        return all(k == "scope" for k in self.stack)

    def struct(self):
        return next((n for n in reversed(self.names) if n), None)

    def comment_run(self, i):
        """A run of comment-only lines from i: documentation of what follows, or a plain comment."""
        line = self.lines[i]
        stripped = line.lstrip()
        col = len(line) - len(stripped)
        if self.at_scope() and col == self.trailing_col and not stripped.startswith("///"):
            self.out.append(line[:col] + "///<" + stripped[2:])
            return i + 1
        if stripped.startswith("// ----"):  # a section rule is never documentation; what follows it may be
            self.out.append(line)
            self.trailing_col = -1
            return i + 1
        j = next_code(self.lines, i)
        run = self.lines[i:j]
        doc = self.at_scope() and documents(self.lines, j) and not any(
            r.lstrip().startswith(("// SPDX", "///")) for r in run)
        # A comment above several members (`// [R] per r:` and three lines of arrays) documents each of them: a
        # Doxygen member group whose first member carries the comment (DISTRIBUTE_GROUP_DOC gives it to all).
        n = member_run(self.lines, j) if doc else 0
        several = n > 1 or (n == 1 and declarators(split_comment(self.lines[j])[0]))
        for k, r in enumerate(run):
            s = r.lstrip()
            opener = "/** @{ */ " if several and k == 0 else ""
            self.out.append(r[:len(r) - len(s)] + opener + "///" + s[2:] if doc else r)
        if several:
            self.group_end = j + n - 1
        elif doc:
            self.commented = j  # the member below has its documentation: no field help appended
        self.trailing_col = -1
        return j

    def code_line(self, i):
        line = self.lines[i]
        code, col = split_comment(line)
        self.trailing_col = -1
        member = self.at_scope() and self.stack and self.stack[-1] == "scope" and is_member(code)
        text = line[col + 2:].strip() if col >= 0 else ""
        if member and (several := declarators(code)):
            # `long iterations = 10000, transient = 1000;  // text`: Doxygen documents only the last declarator
            # of such a line, so each becomes a declaration of its own with the comment, on the same line.
            indent = code[:len(code) - len(code.lstrip())]
            line = indent + " ".join(f"{d};{self.doc(d, text)}" for d in several)
        elif member and col < 0 and i != self.commented:
            line = line + self.doc(code, "")
        elif col >= 0 and self.at_scope() and code.strip() and not code.lstrip().startswith("#") \
                and code.rstrip().endswith((";", ",")) and not line.startswith("///", col):
            line = line[:col] + "///<" + line[col + 2:]
            self.trailing_col = col
        self.braces(code)
        self.out.append(line)

    def doc(self, declaration, text):
        """The documentation of one declarator: the line's comment, else its field's help, else none."""
        name = re.split(r"[={;]", declaration)[0].split()[-1].lstrip("*&")
        text = text or self.helps.get((self.struct(), name), "")
        return f" /**< {text.replace('*/', '* /')} */" if text else ""

    def braces(self, code):
        for b in braces(code):
            if b == "{":
                head = self.pending + code.split("{")[0]
                scope = SCOPE_OPENER.search(head) and "(" not in head.split("=")[0]
                self.stack.append("scope" if scope else "body")
                m = STRUCT_NAME.search(head) if scope else None
                self.names.append(m.group(1) if m else None)
                self.pending = ""
            elif self.stack:
                self.stack.pop()
                self.names.pop()
        self.pending = "" if code.rstrip().endswith((";", "{", "}")) or not code.strip() else self.pending + " " + code

    def run(self):
        i, closing = 0, False
        while i < len(self.lines):
            line, start = self.lines[i], len(self.out)
            stripped = line.lstrip()
            continuation = stripped.startswith("//") and len(line) - len(stripped) == self.trailing_col
            if stripped.startswith("//"):
                j = self.comment_run(i)
            else:
                self.code_line(i)
                j = i + 1
            # A member group closes at the first line after its last member (and that member's comment, which a
            # `/** @} */` on the member's own line would end): the marker opens that line.
            if closing and not continuation:
                self.out[start] = "/** @} */ " + self.out[start]
                closing = False
            if self.group_end in range(i, j):
                closing = True
            i = j
        if closing:
            self.out[-1] += " /** @} */"
        return self.out


def join_literals(lines):
    """Adjacent string literals on consecutive lines joined into the first line (the later lines left empty, so that
    every line keeps its place): Breathe's C++ parser reads `= "a" "b";`, which Doxygen puts on one line, as the end
    of the declaration after "a"."""
    out = list(lines)
    i = 0
    while i < len(out):
        code, col = split_comment(out[i])
        j = i + 1
        while col < 0 and code.rstrip().endswith('"') and j < len(out) and out[j].lstrip().startswith('"'):
            code = code.rstrip()[:-1] + out[j].lstrip()[1:]
            out[j] = ""
            code, col = split_comment(code)
            j += 1
        if j > i + 1:
            out[i] = code
        i = j
    return out


def filter_lines(lines):
    return Filter(join_literals(lines)).run()


def main():
    text = open(sys.argv[1], encoding="utf-8").read()
    lines = text.split("\n")
    sys.stdout.write("\n".join(filter_lines(lines)))


if __name__ == "__main__":
    main()
