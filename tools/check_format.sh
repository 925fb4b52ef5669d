#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checks the C++ files changed since BASE against the repository's .clang-format, changing nothing
# (clang-format --dry-run --Werror): the code base is not reformatted, only what a change touches is held to it.
# Usage: tools/check_format.sh [--lines] [BASE]
#   BASE     a commit (default: the merge base with main, else HEAD): files changed from it to the working tree,
#            committed or not, plus untracked ones
#   --lines  only the changed lines (clang-format-diff on `git diff -U0 BASE`), for files that predate the style
# Exit 0 when every checked file (or line) is formatted, 1 otherwise with clang-format's diagnostics, 2 on usage.
# tools/format.sh holds the whole tree to the same style (the CTest test format_check); this script is the quick
# look at what a change touched.  The configure templates (*.hpp.in) are not C++: clang-format would split their
# @VARIABLE@ placeholders.
set -euo pipefail
cd "$(dirname "$0")/.."
lines=0
if [ "${1:-}" = "--lines" ]; then lines=1; shift; fi
[ $# -le 1 ] || { echo "usage: tools/check_format.sh [--lines] [BASE]" >&2; exit 2; }
cf=$(command -v clang-format || command -v clang-format-14 || true)
[ -n "$cf" ] || { echo "check_format: clang-format not found (apt-get install clang-format)" >&2; exit 2; }
[ -f .clang-format ] || { echo "check_format: no .clang-format at the repository's root" >&2; exit 2; }
base=${1:-$(git merge-base HEAD main 2>/dev/null || git rev-parse HEAD)}
git rev-parse --verify --quiet "$base^{commit}" > /dev/null || { echo "check_format: BASE '$base' is not a commit" >&2; exit 2; }
patterns=('*.cpp' '*.hpp' '*.h')
if [ $lines -eq 1 ]; then
  cfd=$(command -v clang-format-diff || command -v clang-format-diff-14 || true)
  [ -n "$cfd" ] || { echo "check_format: clang-format-diff not found" >&2; exit 2; }
  out=$(git diff -U0 --no-color "$base" -- "${patterns[@]}" | "$cfd" -p1 -binary "$cf" -style=file)
  if [ -n "$out" ]; then printf '%s\n' "$out"; echo "check_format: changed lines not formatted (diff above)"; exit 1; fi
  echo "check_format: changed lines since ${base:0:12} formatted"
  exit 0
fi
mapfile -t files < <({ git diff --name-only --diff-filter=ACMR "$base" -- "${patterns[@]}";
                       git ls-files --others --exclude-standard -- "${patterns[@]}"; } | sort -u)
if [ ${#files[@]} -eq 0 ]; then echo "check_format: no C++ file changed since ${base:0:12}"; exit 0; fi
rc=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  "$cf" --style=file --dry-run --Werror "$f" || rc=1
done
echo "check_format: ${#files[@]} changed C++ files since ${base:0:12}: $([ $rc -eq 0 ] && echo formatted || echo 'not formatted (above)')"
exit $rc
