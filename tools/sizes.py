#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The lab's size limits: no source file in src/ or python/ over 700 lines, no function over 60.

Usage: tools/sizes.py [--exceptions FILE] [ROOT]
  ROOT         the repository (default: this script's parent folder's parent)
  --exceptions a file of known findings to accept, one a line (`#` starts a comment): a file's path
               (`src/cli/main.cpp`) accepts that file's length, `PATH:NAME` (`src/cli/main.cpp:run`) accepts the
               function NAME in PATH (every overload of it).
Prints every finding, one a line (`PATH: N lines (limit 700)`, `PATH:LINE: function NAME N lines (limit 60)`),
marks the accepted ones, names accepted entries that no longer match anything, and exits 1 when a finding is not
accepted, 0 otherwise (2 on usage).

The rule, kept simple on purpose:
- The files: *.cpp, *.hpp, *.h and *.py under src/ and python/ (the configure templates *.in are left out).
- A file's length is its number of lines; comments and blank lines count.
- A C++ function runs from the first line of its definition (its `template <...>` line when it has one) to the
  line of its closing brace, both counted; comments and blank lines inside count.  A definition is a `{` met
  outside any function body whose text since the previous `;`, `{` or `}` ends with a parameter list `)`,
  optionally followed by qualifiers (const, noexcept, override, final, &, &&), a trailing return type or a
  constructor's initialiser list; `if`/`for`/`while`/`switch`/`catch` heads are not definitions.  Lambdas and
  local classes inside a function are counted with their function; a lambda stored at namespace scope counts as
  a function of its own.  Comments, string and character literals and preprocessor lines are blanked first, so
  their braces do not count.
- A Python function runs from its `def` line (its first decorator line when it has one) to its last non-blank
  line indented deeper than the `def`; nested functions count with the enclosing one and on their own.
"""
import os
import re
import sys

FILE_LIMIT = 700
FUNCTION_LIMIT = 60
FOLDERS = ("src", "python")
CPP_SUFFIXES = (".cpp", ".hpp", ".h")

CONTROL = re.compile(r"^(if|for|while|switch|catch|do|else|try)\b")
# The end of a function head: `)` then qualifiers, an optional trailing return type.
FUNCTION_END = re.compile(
    r"\)\s*((const|volatile|noexcept|override|final|mutable|&&|&)\s*|noexcept\s*\([^()]*\)\s*)*"
    r"(->\s*[^;{}]+)?$")
# A constructor's initialiser list after the parameter list: `) : member(...), other{...}`.
INITIALISER_LIST = re.compile(r"\)\s*(noexcept\s*)?:(?!:)")
SCOPE_HEAD = re.compile(r"\b(namespace|class|struct|union|enum|extern)\b")
ACCESS = re.compile(r"\b(public|private|protected)\s*:(?!:)")
NAME = re.compile(r"(operator\s*\S+?|~?[A-Za-z_][A-Za-z_0-9]*(\s*::\s*~?[A-Za-z_][A-Za-z_0-9]*)*)\s*(<[^()]*>)?\s*\($")


def blank_cpp(text):
    """The text with comments, string/character literals and preprocessor lines replaced by spaces (newlines
    kept), so that only code braces and parentheses remain."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            # A preprocessor line, with its backslash continuations.
            while i < n and not (text[i] == "\n" and text[i - 1] != "\\"):
                out.append("\n" if text[i] == "\n" else " ")
                i += 1
            continue
        if c == "/" and text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.extend("\n" if ch == "\n" else " " for ch in text[i:end])
            i = end
            continue
        if c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            delimiter = text[i + 2:text.find("(", i + 2)]
            end = text.find(")" + delimiter + '"', i)
            end = n if end < 0 else end + len(delimiter) + 2
            out.extend("\n" if ch == "\n" else " " for ch in text[i:end])
            out.append('""')
            i = end
            continue
        if c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():
                out.append(" ")  # a digit separator (1'000'000)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * max(0, min(j, n) - i - 1) + c)
            i = j + 1
            continue
        if c == "\n":
            line_start = True
        elif not c.isspace():
            line_start = False
        out.append(c)
        i += 1
    return "".join(out)


def function_name(head):
    """The name of the function whose (flattened) head is given: the qualified name before the parameter list."""
    depth = 0
    for k in range(len(head) - 1, -1, -1):
        if head[k] == ")":
            depth += 1
        elif head[k] == "(":
            depth -= 1
            if depth == 0:
                match = NAME.search(head[:k + 1])
                if match and not INITIALISER_LIST.search(head[:k + 1]):
                    return re.sub(r"\s+", "", match.group(1))
    lambda_owner = re.search(r"([A-Za-z_][A-Za-z_0-9]*)\s*[=(]\s*\[", head)
    return lambda_owner.group(1) if lambda_owner else "?"


def is_function_head(head):
    """Whether the text since the previous `;`, `{` or `}` is a function definition's head (see the rule above)."""
    flat = " ".join(ACCESS.sub(" ", head).split())
    if not flat or CONTROL.match(flat) or flat.endswith("="):
        return False
    return bool(FUNCTION_END.search(flat)) and not SCOPE_HEAD.match(flat)


def is_scope_head(flat):
    """Whether a (flattened) head opens a namespace, class, struct, union, enum or extern block: a scope keyword
    outside template argument lists, and no `=` (which would make the brace an initialiser)."""
    if flat.rstrip().endswith("="):
        return False
    outside = flat
    while True:
        shorter = re.sub(r"<[^<>]*>", "", outside)
        if shorter == outside:
            break
        outside = shorter
    return not flat or bool(SCOPE_HEAD.search(outside))


def cpp_functions(text):
    """(first line, last line, name) of every function defined outside a function body, 1-based lines."""
    code = blank_cpp(text)
    found = []
    stack = []  # one entry a brace: "scope" (namespace/class/...), "function", "inner" (inside a function), "expr"
    head_start = 0  # where the text since the last ; { } at a non-function level begins
    line = 1
    function_start = []  # (line, name) for the open function
    for k, c in enumerate(code):
        if c == "\n":
            line += 1
            continue
        if c not in "{};":
            continue
        inside = stack and stack[-1] in ("function", "inner")
        if c == "{":
            if inside:
                stack.append("inner")
                continue
            if stack and stack[-1] == "expr":
                stack.append("expr")
                continue
            head = code[head_start:k]
            flat = " ".join(ACCESS.sub(" ", head).split())
            if is_function_head(head):
                lead = head[:len(head) - len(head.lstrip())]
                first = line - head.count("\n") + lead.count("\n")
                stack.append("function")
                function_start.append((first, function_name(flat)))
            elif is_scope_head(flat):
                stack.append("scope")
                head_start = k + 1
            else:
                stack.append("expr")  # a braced initialiser: its text stays part of the head
            continue
        if c == "}":
            kind = stack.pop() if stack else "scope"
            if kind == "function":
                first, name = function_start.pop()
                found.append((first, line, name))
                head_start = k + 1
            elif kind == "scope":
                head_start = k + 1
            continue
        if c == ";" and not inside and not (stack and stack[-1] == "expr"):
            head_start = k + 1
    return found


def python_functions(text):
    """(first line, last line, name) of every `def`, 1-based lines."""
    lines = text.split("\n")
    found = []
    for i, source in enumerate(lines):
        match = re.match(r"^(\s*)(async\s+)?def\s+([A-Za-z_0-9]+)", source)
        if not match:
            continue
        indent = len(match.group(1))
        first = i
        while first > 0 and lines[first - 1].strip().startswith("@") and \
                len(lines[first - 1]) - len(lines[first - 1].lstrip()) == indent:
            first -= 1
        last = i
        for j in range(i + 1, len(lines)):
            body = lines[j]
            if not body.strip():
                continue
            if len(body) - len(body.lstrip()) <= indent:
                break
            last = j
        found.append((first + 1, last + 1, match.group(3)))
    return found


def source_files(root):
    for folder in FOLDERS:
        for directory, subdirs, names in os.walk(os.path.join(root, folder)):
            subdirs[:] = sorted(d for d in subdirs if d not in ("__pycache__",) and not d.startswith("."))
            for name in sorted(names):
                if name.endswith(CPP_SUFFIXES) or name.endswith(".py"):
                    yield os.path.relpath(os.path.join(directory, name), root)


def findings(root):
    """(key, message) of every finding; key is the path for a file, PATH:NAME for a function."""
    result = []
    for path in source_files(root):
        with open(os.path.join(root, path), encoding="utf-8") as handle:
            text = handle.read()
        count = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
        if count > FILE_LIMIT:
            result.append((path, f"{path}: {count} lines (limit {FILE_LIMIT})"))
        functions = python_functions(text) if path.endswith(".py") else cpp_functions(text)
        for first, last, name in functions:
            length = last - first + 1
            if length > FUNCTION_LIMIT:
                result.append((f"{path}:{name}",
                               f"{path}:{first}: function {name} {length} lines (limit {FUNCTION_LIMIT})"))
    return result


def read_exceptions(path):
    accepted = set()
    with open(path, encoding="utf-8") as handle:
        for raw in handle:
            entry = raw.split("#", 1)[0].strip()
            if entry:
                accepted.add(entry)
    return accepted


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    exceptions = None
    args = list(argv)
    while args:
        arg = args.pop(0)
        if arg == "--exceptions" and args:
            exceptions = args.pop(0)
        elif not arg.startswith("-") and not args:
            root = arg
        else:
            print("usage: tools/sizes.py [--exceptions FILE] [ROOT]", file=sys.stderr)
            return 2
    accepted = read_exceptions(exceptions) if exceptions else set()
    found = findings(root)
    failing = 0
    for key, message in found:
        if key in accepted:
            print(f"{message} [accepted]")
        else:
            print(message)
            failing += 1
    for stale in sorted(accepted - {key for key, _ in found}):
        print(f"note: accepted {stale} is no longer a finding; remove it from the exceptions")
    print(f"sizes: {len(found)} findings, {failing} not accepted")
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
