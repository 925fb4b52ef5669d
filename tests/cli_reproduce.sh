#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# `btob run results/X/X.json` is a reproduction check: without --out it writes into X/reproduced/ (never over the
# original, whose files keep their bytes), prints "reproduction: N of M datasets bit-identical[; differ: ...]", writes
# the same as reproduced/reproduction.json and exits 0 whether or not the data are the same; --out naming the
# original folder is refused (exit 2); a scene (.toml) runs as before, into its own folder.
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"
cd "$out" || exit 1

# A small result with arrays and decimal-text datasets (windows bounds: NAME.h5).
"$btob" windows bounds --n 2..6 --digits 20 --out X --name X --quiet || { echo "FAIL: the first run"; exit 1; }
before=$(md5sum X/X.h5 X/X.json)
report=$("$btob" run X/X.json --quiet --no-plot) || { echo "FAIL: btob run X/X.json exited $?"; fail=1; }
[ "$(md5sum X/X.h5 X/X.json)" = "$before" ] || { echo "FAIL: the re-run changed the original's files"; fail=1; }
[ -f X/reproduced/X.h5 ] || { echo "FAIL: no X/reproduced/X.h5 ($(ls -R X))"; fail=1; }
grep -Eq "^reproduction: ([0-9]+) of \1 datasets bit-identical$" <<<"$report" ||
  { echo "FAIL: the report of an identical re-run: '$report'"; fail=1; }
python3 - X/reproduced/reproduction.json <<'EOF' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
assert j["reproduced"] is True and j["differ"] == [] and j["identical_count"] == j["compared"] > 2, j
assert "lower_bound_decimal" in j["identical"], j["identical"]
EOF

# An original whose data differ (another request's NAME.h5 put in its place): exit 0, the datasets that differ named.
"$btob" windows bounds --n 2..6 --digits 25 --out Y --name X --quiet || fail=1
cp Y/X.h5 X/X.h5
report=$("$btob" run X/X.json --quiet --no-plot) || { echo "FAIL: a re-run that differs exited $?"; fail=1; }
grep -q "^reproduction: [0-9]* of [0-9]* datasets bit-identical; differ: .*lower_bound_decimal" <<<"$report" ||
  { echo "FAIL: the report of a differing re-run: '$report'"; fail=1; }
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert not j['reproduced'] and 'lower_bound_decimal' in j['differ'], j" \
  X/reproduced/reproduction.json || fail=1

# --out: where the user says, but never the original folder.
"$btob" run X/X.json --out Z --quiet --no-plot > /dev/null && [ -f Z/X.h5 ] && [ -f Z/reproduction.json ] ||
  { echo "FAIL: btob run X/X.json --out Z"; fail=1; }
expect_error "--out: got 'X', the manifest's own folder" run X/X.json --out X
expect_error "the manifest's own folder" run X/X.json --out ./X/

# A scene runs as before: into results/<scene name> (its own out here), no reproduction report.
printf 'command = "windows thresholds"\n[args]\ndigits = "12"\nout = "S"\n' > s.toml
report=$("$btob" run s.toml --quiet) || { echo "FAIL: btob run s.toml"; fail=1; }
[ -z "$report" ] && [ ! -e S/reproduced ] || { echo "FAIL: a scene's run reported '$report'"; fail=1; }
[ $fail = 0 ] && echo "cli_reproduce: ok"
exit $fail
