#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tools/sizes.py on a small tree made here: it finds what its rule says and nothing else.

Usage: sizes_test.py REPOSITORY.  Exits 1 with the differences, 0 when every case holds.
"""
import os
import subprocess
import sys
import tempfile


def body(n):
    """n lines of a function body (statements, a comment, a blank line, braces inside a string)."""
    lines = ['  int x = 0;', '  // a comment counts', '', '  const char* s = "{ not a brace";']
    while len(lines) < n:
        lines.append('  ++x;')
    return lines[:n]


def cpp_sources():
    """(path, text, expected findings) of the C++ cases: a function of 61 lines is over, of 60 is not."""
    f61 = ['int over(int a) {'] + body(59) + ['}']
    f60 = ['int at_limit(int a) {'] + body(58) + ['}']
    # A lambda inside counts with its function; a constructor with an initialiser list and a braced member.
    lam = ['template <class T>', 'void with_lambda(T t) {', '  auto f = [&](int k) {'] + body(30) + ['  };'] + \
        body(27) + ['}']
    ctor = ['struct S {', '  S(int a) : a_{a}, b_(a) {'] + ['  ' + l for l in body(59)] + ['  }', '  int a_, b_;', '};']
    text = '\n'.join(['namespace x {'] + f61 + f60 + lam + ctor + ['}  // namespace x']) + '\n'
    return text, ['src/m/a.cpp:over', 'src/m/a.cpp:with_lambda', 'src/m/a.cpp:S']


def main(repo):
    tool = os.path.join(repo, 'tools', 'sizes.py')
    failures = []
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, 'src', 'm'))
        os.makedirs(os.path.join(root, 'python', 'p'))
        text, expected = cpp_sources()
        with open(os.path.join(root, 'src', 'm', 'a.cpp'), 'w') as f:
            f.write(text)
        with open(os.path.join(root, 'src', 'm', 'long.hpp'), 'w') as f:
            f.write('// 701 lines\n' + '\n' * 700)
        with open(os.path.join(root, 'src', 'm', 'short.hpp'), 'w') as f:
            f.write('// 700 lines\n' + '\n' * 699)
        py = ['def over():'] + ['    x = 1'] * 60 + ['', 'def at_limit():'] + ['    x = 1'] * 59 + ['']
        with open(os.path.join(root, 'python', 'p', 'b.py'), 'w') as f:
            f.write('\n'.join(py))
        expected += ['src/m/long.hpp', 'python/p/b.py:over']
        run = subprocess.run([sys.executable, tool, root], capture_output=True, text=True)
        found = [line for line in run.stdout.splitlines() if not line.startswith('sizes:')]
        keys = sorted(line.split(' ')[0].rstrip(':').rsplit(':', 1)[0] + ':' + line.split(' function ')[1].split()[0]
                      if ' function ' in line else line.split(':')[0] for line in found)
        if keys != sorted(expected):
            failures.append(f'found {keys}, expected {sorted(expected)}\n{run.stdout}')
        if run.returncode != 1:
            failures.append(f'exit {run.returncode} with findings, expected 1')
        exceptions = os.path.join(root, 'exceptions.txt')
        with open(exceptions, 'w') as f:
            f.write('# all known\n' + '\n'.join(expected) + '\nsrc/m/gone.cpp\n')
        run = subprocess.run([sys.executable, tool, '--exceptions', exceptions, root], capture_output=True, text=True)
        if run.returncode != 0 or 'src/m/gone.cpp is no longer a finding' not in run.stdout:
            failures.append(f'with every finding accepted: exit {run.returncode}, output\n{run.stdout}')
    for failure in failures:
        print('FAIL:', failure)
    if not failures:
        print('sizes_test: every case holds')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1]))
