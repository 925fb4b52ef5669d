#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The loops of a compiled function and what one pass of each executes, read from the generated code.

Usage: analyses/loop_instructions.py BINARY FUNCTION [--min N]

FUNCTION is a substring of the demangled name (the first function whose name contains it is read; its out-of-line
clones too).  Every backward conditional jump closes a loop; for each loop the instructions between its target and
the jump are counted: all, vector (v-prefixed), with a memory operand, divisions and square roots.  Nested loops
are listed each (an outer loop's count includes its inner loops once).  This is the count that bounds a kernel on
a core that issues about one 512-bit instruction per cycle, and, unlike a timing, it does not move with the load of
a shared machine: the README's ceilings of the tangent-cocycle, covariant-vector and rotation loops come from it.

Example (the covariant vectors' window step, two 8-lane vectors per pass):
  analyses/loop_instructions.py build/release/benchmarks/bm_lyapunov 'clv_phase<true, true, false>'
"""
import argparse
import re
import signal
import subprocess
import sys


def functions(binary):
    """Yields (name, [(address, mnemonic, operands)]) for every function of the binary's text."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-C", binary], check=True, capture_output=True,
                         text=True).stdout
    name, body = None, []
    for line in out.splitlines():
        head = re.match(r"[0-9a-f]+ <(.*)>:$", line)
        if head:
            if name is not None:
                yield name, body
            name, body = head.group(1), []
            continue
        ins = re.match(r"\s+([0-9a-f]+):\s+(\S+)\s*(.*)", line)
        if ins and name is not None:
            body.append((int(ins.group(1), 16), ins.group(2), ins.group(3)))
    if name is not None:
        yield name, body


def loops(body):
    """(start, end, instructions) of every loop closed by a backward conditional jump, innermost first."""
    found = []
    for address, op, args in body:
        if not op.startswith("j") or op == "jmp":
            continue
        target = re.match(r"([0-9a-f]+)\b", args)
        if not target:
            continue
        start = int(target.group(1), 16)
        if start < address:
            found.append((start, address, [b for b in body if start <= b[0] <= address]))
    return sorted(found, key=lambda f: (len(f[2]), f[0]))


def main():
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet under head
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("function")
    parser.add_argument("--min", type=int, default=20, help="smallest loop listed (instructions), default 20")
    a = parser.parse_args()
    matched = [(n, b) for n, b in functions(a.binary) if a.function in n and b]
    if not matched:
        sys.exit(f"function: no function of {a.binary} has '{a.function}' in its name")
    for name, body in matched:
        print(f"{name[:150]}{'...' if len(name) > 150 else ''}: {len(body)} instructions")
        for start, end, ins in loops(body):
            if len(ins) < a.min:
                continue
            vec = sum(op.startswith("v") for _, op, _ in ins)
            mem = sum("(%" in args and not op.startswith(("lea", "nop")) for _, op, args in ins)
            div = sum(op.startswith(("vdiv", "div", "vsqrt", "sqrt")) for _, op, _ in ins)
            print(f"  loop {start:x}-{end:x}: {len(ins):5d} instructions, {vec:5d} vector, {mem:4d} with memory, "
                  f"{div:3d} divisions/roots")


if __name__ == "__main__":
    main()
