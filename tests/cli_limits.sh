#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The limits the documentation states, at their edges: `digits` fields accept 10 and 10000 and refuse 9 and 10001;
# every error that advises an option names one the same command accepts (the advised command line, run, is not
# refused); an error quotes at most about 80 characters of an offending input (a word of 100002 symbols); a sweep
# whose values would collapse to fewer distinct doubles than requested is refused (exit 2, one line naming the
# fields and how many distinct doubles the range holds).
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

# ---- digits: the documented 10..10000, at both edges ----
accepts() {  # accepts <btob arguments...>: exit 0
  local err
  if err=$("$btob" "$@" 2>&1 >/dev/null); then echo "ok: accepted: btob $*"; else
    echo "FAIL (exit $?, expected 0): btob $*"; echo "  $err" | head -c 400; echo; fail=1
  fi
}
accepts windows bounds --n 2 --digits 10
accepts windows bounds --n 2 --digits 10000  # refused as "got 10005" when r_crit,2 added its guard digits to digits
accepts windows thresholds --digits 10000
accepts windows stripes --max-m 6 --digits 10000
for cmd in "windows bounds --n 2" "windows thresholds" "windows stripes --max-m 6"; do
  # shellcheck disable=SC2086
  expect_error "digits: got 9, expected 10..10000" $cmd --digits 9
  # shellcheck disable=SC2086
  expect_error "digits: got 10001, expected 10..10000" $cmd --digits 10001
done

# ---- advice: "use --OPTION VALUE" in an error names a value the same command accepts ----
# advised <btob arguments...>: the error's advice, applied to the same command line, is not refused (run as a dry
# run: validation is what is checked, not the run).  A command without the option must give no such advice.
advised() {
  local err fix opt val
  err=$("$btob" "$@" 2>&1 >/dev/null)
  fix=$(grep -o -- 'use --[a-z-]* [^ ;,)]*' <<<"$err" | head -1)
  if [ -z "$fix" ]; then
    echo "FAIL (no advice): btob $* -> $err"; fail=1; return
  fi
  read -r _ opt val <<<"$fix"
  local args=() a skip=0
  for a in "$@"; do  # the same command line with the advised value in place of the option's
    if [ $skip = 1 ]; then skip=0; continue; fi
    if [ "$a" = "$opt" ]; then skip=1; continue; fi
    args+=("$a")
  done
  local err2
  if err2=$("$btob" "${args[@]}" "$opt" "$val" --dry-run 2>&1 >/dev/null); then
    echo "ok: btob $* advises '$opt $val', accepted"
  else
    echo "FAIL (the advised '$opt $val' is refused): btob $*"; echo "  $err -> $err2"; fail=1
  fi
}
no_advice() {  # no_advice <btob arguments...>: refused (exit 2) without naming an option the command lacks
  local err rc
  err=$("$btob" "$@" 2>&1 >/dev/null)
  rc=$?
  if [ $rc -ne 2 ] || grep -q -- "use --precision" <<<"$err"; then
    echo "FAIL (exit $rc; advice to a command without --precision): btob $* -> $err"; fail=1
  else echo "ok: btob $* -> $err"; fi
}
orbit=(--point 1,-0.5,-1.1)
advised lyapunov --r 1e-300 "${orbit[@]}"                      # mpfr:604
advised lyapunov --r 1e-7 "${orbit[@]}"                        # long-double
advised lyapunov --r 1e-7 "${orbit[@]}" --precision float     # the narrowest accepted that resolves it
advised lyapunov-map --r-min 1e-3 --r-max 0.2 --r-count 2 --grid 1,-0.5,-1.1 --precision float  # double
no_advice lyapunov-map --r-min 1e-300 --r-max 0.2 --r-count 2 --grid 1,-0.5,-1.1  # float or double only
no_advice lyapunov-strip --r 1e-300 --precision double
no_advice classify --r 1e-300 "${orbit[@]}"                   # advised mpfr:604, which classify has no option for
no_advice basins --r 1e-300 --grid strip:2x2
no_advice basins-r --r-values 1e-300 --grid 1,-0.5,-1.1
no_advice bifurcation --r-min 1e-300 --r-max 0.2 --r-count 2 --attractors --out "$out/b"

# ---- a long input is quoted in at most ~80 characters, with its length ----
word=$(head -c 100000 /dev/zero | tr '\0' '1')"4x"  # 100002 symbols, the last two not over 1, 2, 3
err=$("$btob" pattern "$word" --r 0.5 2>&1 >/dev/null)
rc=$?
len=$(printf '%s' "$err" | wc -c)
if [ $rc -ne 2 ] || [ "$len" -gt 400 ] || ! grep -q "(100002 characters)" <<<"$err"; then
  echo "FAIL (exit $rc, $len characters, expected exit 2 and a short line with the length): $(head -c 300 <<<"$err")"
  fail=1
else echo "ok: a word of 100002 symbols -> $err"; fi
err=$("$btob" lyapunov --r 0.2 --point "1,-0.5,$(head -c 5000 /dev/zero | tr '\0' '9')x" 2>&1 >/dev/null)
len=$(printf '%s' "$err" | wc -c)
[ "$len" -le 400 ] || { echo "FAIL ($len characters): a point of 5000 characters quoted whole"; fail=1; }

# ---- sweeps whose values collapse to fewer distinct doubles than requested ----
collapse=(--r-min 0.2 --r-max 0.20000000000000004 --r-count 5000)  # 0.2 and the next double: two doubles
expect_error "r-count: got 5000 values over r-min..r-max = \[0.2, 0.20000000000000004\], expected at most 2 (the distinct doubles" \
  bifurcation "${collapse[@]}" --iterations 10 --tail 5 --grid 1,-0.5,-1.1 --out "$out/b"
expect_error "(the distinct doubles in that range" lyapunov-map "${collapse[@]}" --iterations 100 --grid 1,-0.5,-1.1 --out "$out/b"
expect_error "(the distinct doubles in that range" hyperbolicity-orbits "${collapse[@]}" --grid 1,-0.5,-1.1 --out "$out/b"
expect_error "(the distinct doubles in that range" basins-r "${collapse[@]}" --grid 1,-0.5,-1.1 --out "$out/b"
expect_error "(the distinct doubles in that range" transfer-r "${collapse[@]}" --out "$out/b"
expect_error "(the distinct doubles in that range" pattern-curves --word 132312 "${collapse[@]}" --out "$out/b"
expect_error "bins: got 5000 values over range" bifurcation --r-count 2 --iterations 10 --tail 5 --grid 1,-0.5,-1.1 \
  --range 0.5 0.5000000000000001 --bins 5000 --out "$out/b"
expect_error "grid: got 4 values over w1min:w1max" lyapunov-strip --r 0.2 --grid strip:4x2:1:1.0000000000000002 --out "$out/b"
# Two doubles hold two values: the edge is accepted.
accepts bifurcation --r-min 0.2 --r-max 0.20000000000000004 --r-count 2 --iterations 10 --tail 5 --grid 1,-0.5,-1.1 \
  --dry-run
[ -e "$out/b" ] && { echo "FAIL: output written despite errors: $(ls "$out/b")"; fail=1; }
exit $fail
