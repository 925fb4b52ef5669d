#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Holds every C++ file of the repository to its .clang-format (the house style, tuned to clang-format 14).
# Usage: tools/format.sh [--fix]
#   (no option)  check: change nothing, print clang-format's findings and how many, exit 1 when there is any
#   --fix        reformat every C++ file in place (then rebuild and run the tests: include order may change)
# The files: the tracked *.cpp, *.hpp, *.h and *.c (git ls-files; outside a git checkout, those under src, tests, python,
# benchmarks and examples).  The configure templates (*.hpp.in) are left out: clang-format would split their
# @VARIABLE@ placeholders.  Exit 2 on usage, or when clang-format 14 is missing (another version formats otherwise).
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
case "${1:-}" in
  --fix) fix=1 ;;
  "") ;;
  *) echo "usage: tools/format.sh [--fix]" >&2; exit 2 ;;
esac
[ $# -le 1 ] || { echo "usage: tools/format.sh [--fix]" >&2; exit 2; }
cf=$(command -v clang-format-14 || command -v clang-format || true)
[ -n "$cf" ] || { echo "format: clang-format not found (apt-get install clang-format, version 14)" >&2; exit 2; }
"$cf" --version | grep -q "version 14\." \
  || { echo "format: $cf is not clang-format 14 ($("$cf" --version)); the style is tuned to 14" >&2; exit 2; }
[ -f .clang-format ] || { echo "format: no .clang-format at the repository's root" >&2; exit 2; }
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h' '*.c')
else
  mapfile -t files < <(find src tests python benchmarks examples -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.c' \) | sort)
fi
[ ${#files[@]} -gt 0 ] || { echo "format: no C++ file found" >&2; exit 2; }
if [ $fix -eq 1 ]; then
  "$cf" --style=file -i "${files[@]}"
  echo "format: ${#files[@]} C++ files reformatted with .clang-format"
  exit 0
fi
out=$("$cf" --style=file --dry-run "${files[@]}" 2>&1) || { printf '%s\n' "$out" >&2; echo "format: clang-format failed" >&2; exit 2; }
findings=$(printf '%s\n' "$out" | grep -c ': warning: code should be clang-formatted' || true)
if [ "$findings" -gt 0 ]; then
  printf '%s\n' "$out"
  nfiles=$(printf '%s\n' "$out" | grep ': warning: code should be clang-formatted' | cut -d: -f1 | sort -u | wc -l)
  echo "format: $findings findings in $nfiles of ${#files[@]} C++ files (above); tools/format.sh --fix reformats them"
  exit 1
fi
echo "format: ${#files[@]} C++ files formatted"
