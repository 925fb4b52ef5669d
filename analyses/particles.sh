#!/usr/bin/env bash
# Regenerates results/particles (issue 19): periodic collapses realised by four particles, and every periodic
# orbit of P_r, stable or not.
#   atlas/        btob pattern atlas --feasible: every canonical word of length <= L with a feasible periodic point
#                 (feasible.csv, feasible_counts.csv, unstable_followed.csv, feasible.json, feasible.png)
#   <word>_<r>/   btob particles: the three cases checked against the map and the exact period matrix, with the
#                 space-time diagram and the animation (spacetime.png, animation.gif)
#   realised.csv  the particle check of every stable word of the atlas (middle of each stability interval) and of
#                 the windows 1^n 3^n, n = 1..10 (middle of the window; n = 1 is never stable: middle of its
#                 feasible interval)
# Usage: analyses/particles.sh [path/to/btob] [L]   (run from the repository root)
set -euo pipefail
BTOB=${1:-build/release/btob}
L=${2:-14}
OUT=results/particles
PERIODS=10000
mkdir -p "$OUT"

"$BTOB" pattern atlas --feasible --max-length "$L" --out "$OUT/atlas"

for case in "1133 0.15" "111333 0.1" "132312 0.5" "13223122 0.2"; do
  set -- $case
  "$BTOB" particles "$1" --r "$2" --periods $PERIODS --out "$OUT/${1}_r$2" >/dev/null
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The words and r values: stable intervals of the atlas, then the windows.
/usr/bin/python3 - "$OUT/atlas/feasible.csv" > "$tmp/cases" <<'PY'
import csv, sys
with open(sys.argv[1], newline="") as f:
    for row in csv.DictReader(f):
        if row["outcome"] == "stable":
            lo, hi = float(row["r_low"]), float(row["r_high"])
            print(row["digits"], repr((lo + hi) / 2), "atlas")
PY
for n in $(seq 1 10); do
  w="$(printf '1%.0s' $(seq "$n"))$(printf '3%.0s' $(seq "$n"))"
  win=$("$BTOB" pattern "$w" --window | sed -n 2p)
  if [ -z "$win" ]; then  # never stable (n = 1): the middle of its feasible interval
    mid=$(awk -F, -v w="13" '$2 == w && $7 == "unstable" { print ($5 + $6) / 2; exit }' "$OUT/atlas/feasible.csv")
  else
    mid=$(echo "$win" | awk -F, '{ printf "%.17g", ($2 + $3) / 2 }')
  fi
  echo "$w $mid window" >> "$tmp/cases"
done
echo "word,r,sequence_ok,contraction,predicted,outcome,letters,time_contraction,time_predicted,velocity_contraction,velocity_predicted,time_to_collapse,source" > "$tmp/realised.csv"
i=0
while read -r w r src; do
  i=$((i + 1))
  "$BTOB" particles "$w" --r "$r" --periods $PERIODS --out "$tmp/run$i" --no-plot >/dev/null 2>&1 ||
    { echo "particles: $w at r = $r failed" >&2; continue; }
  /usr/bin/python3 - "$tmp/run$i/particles.csv" "$src" >> "$tmp/realised.csv" <<'PY'
import csv, sys
row = next(csv.DictReader(open(sys.argv[1], newline="")))
print(",".join([row["word"], row["r"], row["sequence_ok"], row["contraction"], row["predicted"], row["outcome"],
                row["letters"], row["time_contraction"], row["time_predicted"], row["velocity_contraction"],
                row["velocity_predicted"], row["time_to_collapse"], sys.argv[2]]))
PY
  rm -rf "$tmp/run$i"
done < "$tmp/cases"
mv "$tmp/realised.csv" "$OUT/realised.csv"
/usr/bin/python3 - "$OUT/realised.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
ok = sum(r["sequence_ok"] == "true" for r in rows)
worst = max(abs(float(r["contraction"]) / float(r["predicted"]) - 1) for r in rows)
print(f"realised.csv: {ok} of {len(rows)} words reproduced for every period; "
      f"max |contraction/predicted - 1| = {worst:.3g}", file=sys.stderr)
PY
