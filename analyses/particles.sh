#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates results/particles: periodic collapses realised by four particles, and every periodic
# orbit of P_r, stable or not.
#   atlas/        btob pattern atlas --feasible: every canonical word of length <= L with a feasible periodic point
#                 (feasible.csv, feasible_counts.csv, feasible_unstable_followed.csv, feasible.h5, feasible.json,
#                 feasible.png)
#   <word>_<r>/   btob particles: the three cases checked against the map and the exact period matrix, with the
#                 space-time diagram and the animation (spacetime.png, animation.gif)
#   realised.csv  the particle check of every stable word of the atlas (middle of each stability interval) and of
#                 the windows 1^n 3^n, n = 1..10 (middle of the window; n = 1 is never stable: middle of its
#                 feasible interval)
# Usage: analyses/particles.sh [path/to/btob] [L]   (run from the repository root; SKIP_ATLAS=1 keeps the atlas)
set -euo pipefail
BTOB=${1:-build/release/btob}
L=${2:-14}
OUT=results/particles
PERIODS=10000
mkdir -p "$OUT"

# SKIP_ATLAS=1 reuses an existing $OUT/atlas (the atlas is the long part: ~10 CPU minutes at L = 14).
[ "${SKIP_ATLAS:-0}" = 1 ] || "$BTOB" pattern atlas --feasible --max-length "$L" --out "$OUT/atlas"

# Three cases (the windows 1133 at r = 0.15 and 111333 at 0.1, and 132312 at 0.5), and the unstable 13223122
# followed in 100-digit arithmetic.
for case in "1133 0.15 double" "111333 0.1 double" "132312 0.5 double" "13223122 0.1 mpfr:100"; do
  set -- $case
  "$BTOB" particles "$1" --r "$2" --periods $PERIODS --precision "$3" --out "$OUT/${1}_r$2" >/dev/null
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The words and r values: stable intervals of the atlas, then the windows.
/usr/bin/python3 - "$OUT/atlas/feasible.csv" > "$tmp/cases" <<'PY'
import csv, sys
with open(sys.argv[1], newline="") as f:
    for row in csv.DictReader(f):
        if row["outcome"] == "stable orbit":
            lo, hi = float(row["r_low"]), float(row["r_high"])
            print(row["digits"], repr((lo + hi) / 2), "atlas")
PY
for n in $(seq 1 10); do
  w="$(printf '1%.0s' $(seq "$n"))$(printf '3%.0s' $(seq "$n"))"
  win=$("$BTOB" pattern "$w" --window | sed -n 2p)
  if [ -z "$win" ]; then  # never stable (n = 1): the middle of its feasible interval
    mid=$(awk -F, -v w="13" '$2 == w && $7 == "unstable orbit" && $8 == "true" { printf "%.17g", ($5 + $6) / 2; exit }' "$OUT/atlas/feasible.csv")
  else
    mid=$(echo "$win" | awk -F, '{ printf "%.17g", ($2 + $3) / 2 }')
  fi
  echo "$w $mid window" >> "$tmp/cases"
done
echo "word,r,sequence_ok,contraction,predicted,digits,outcome,periods_ok,letters,time_contraction,time_predicted,velocity_contraction,velocity_predicted,time_to_collapse,source" > "$tmp/realised.csv"
i=0
while read -r w r src; do
  i=$((i + 1))
  "$BTOB" particles "$w" --r "$r" --periods $PERIODS --out "$tmp/run$i" --no-plot >/dev/null 2>&1 ||
    { echo "particles: $w at r = $r failed" >&2; continue; }
  /usr/bin/python3 - "$tmp/run$i/particles.csv" "$src" >> "$tmp/realised.csv" <<'PY'
import csv, sys
row = next(csv.DictReader(open(sys.argv[1], newline="")))
print(",".join([row["word"], row["r"], row["sequence_ok"], row["contraction"], row["predicted"], row["word_digits"],
                row["outcome"], row["periods_ok"], row["letters"], row["time_contraction"], row["time_predicted"],
                row["velocity_contraction"], row["velocity_predicted"], row["time_to_collapse"], sys.argv[2]]))
PY
  rm -rf "$tmp/run$i"
done < "$tmp/cases"
mv "$tmp/realised.csv" "$OUT/realised.csv"
# Its manifest (the particle runs' own manifests are not kept: realised.csv is their table).
"$(dirname "$BTOB")/btob_manifest" "$OUT/manifest.json" "analyses/particles.sh $BTOB $L" realised.csv
/usr/bin/python3 - "$OUT/realised.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
ok = [r for r in rows if r["sequence_ok"] == "true"]
worst = max(abs(float(r["contraction"]) / float(r["predicted"]) - 1) for r in ok)
print(f"realised.csv: {len(ok)} of {len(rows)} (word, r) reproduced for every period, contraction = prediction to "
      f"{worst:.2g} (relative); the others are not collapses", file=sys.stderr)
PY

# Small summaries of the atlas (feasible.csv and feasible_unstable_followed.csv are hundreds of MB at L = 14: git-ignored).
/usr/bin/python3 - "$OUT/atlas" <<'PY'
import collections, csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "feasible.csv"), newline="")))
RC = 0.1917  # the earlier literature's r_crit (Introduction)
with open(os.path.join(d, "feasible_stable.csv"), "w") as f:  # every stable interval
    w = csv.writer(f, lineterminator="\n")
    w.writerow(["word", "digits", "length", "collisions", "r_low", "r_high", "collapse", "low_reason", "high_reason"])
    for r in rows:
        if r["outcome"] == "stable orbit":
            w.writerow([r[k] for k in ("word", "digits", "length", "collisions", "r_low", "r_high", "collapse", "low_reason",
                                       "high_reason")])
with open(os.path.join(d, "feasible_above_0.17.csv"), "w") as f:  # every interval reaching above 0.17
    w = csv.writer(f, lineterminator="\n")
    w.writerow(list(rows[0].keys()))
    for r in rows:
        if float(r["r_high"]) > 0.17:
            w.writerow(list(r.values()))
by = collections.defaultdict(lambda: dict(feasible=set(), stable=set(), above=set(), stable_above=set(),
                                          collapse=set(), collapse_above=set(), max_collapse_r=0.0))
for r in rows:
    b = by[int(r["length"])]
    word, hi = r["word"], float(r["r_high"])
    b["feasible"].add(word)
    if r["outcome"] == "stable orbit":
        b["stable"].add(word)
    if hi > RC:
        b["above"].add(word)
        if r["outcome"] == "stable orbit":
            b["stable_above"].add(word)
    if r["collapse"] == "true":
        b["collapse"].add(word)
        b["max_collapse_r"] = max(b["max_collapse_r"], hi)
        if hi > RC:
            b["collapse_above"].add(word)
with open(os.path.join(d, "feasible_by_length.csv"), "w") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(["length", "feasible_words", "stable_words", "collapse_words", "feasible_above_0.1917",
                "stable_above_0.1917", "collapse_above_0.1917", "largest_r_with_collapse"])
    for L in sorted(by):
        b = by[L]
        w.writerow([L, len(b["feasible"]), len(b["stable"]), len(b["collapse"]), len(b["above"]), len(b["stable_above"]),
                    len(b["collapse_above"]), f"{b['max_collapse_r']:.17g}"])
# The iterator check of the unstable orbits: rows, rows checked (expansion > 1, prediction within the 2000-period
# cap of btob), rows followed within [predicted/2 - 2, 2 predicted + 2] periods (the rule of btob's summary).
n = checked = agree = 0
for r in csv.DictReader(open(os.path.join(d, "feasible_unstable_followed.csv"), newline="")):
    pred, got, lam = float(r["predicted"]), int(r["followed"]), float(r["expansion"])
    n += 1
    if lam > 1 and got >= 0 and 2 * pred + 2 < 2000:
        checked += 1
        agree += pred / 2 - 2 <= got <= 2 * pred + 2
with open(os.path.join(d, "unstable_followed_summary.csv"), "w") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(["unstable_intervals", "checked", "followed_as_predicted"])
    w.writerow([n, checked, agree])
PY
