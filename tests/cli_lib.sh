#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Shared by the command-line error tests (tests/cli_errors*.sh): source it after setting btob=PATH/TO/btob.
# Provides $out (a temporary directory, removed on exit), $fail, and expect_error.
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail=0

expect_error() {  # expect_error <word the message must contain> <btob arguments...>
  local want="$1"
  shift
  local err rc
  err=$("$btob" "$@" 2>&1 >/dev/null)
  rc=$?
  local lines
  lines=$(printf '%s\n' "$err" | grep -c .)
  if [ "$rc" -ne 2 ]; then
    echo "FAIL (exit $rc, expected 2): btob $*"; echo "  $err"; fail=1
  elif [ "$lines" -ne 1 ]; then
    echo "FAIL ($lines lines, expected one): btob $*"; echo "$err"; fail=1
  elif ! grep -q -- "$want" <<<"$err"; then
    echo "FAIL (message lacks '$want'): btob $*"; echo "  $err"; fail=1
  else
    echo "ok: btob $* -> $err"
  fi
}
