#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The command line's error contract, checked as a user meets it: bad input gets a one-line error that
# names the field, exit status 2, and no output file created or overwritten.
set -u
btob="$1"
source "$(dirname "$0")/cli_lib.sh"

b=(bifurcation --out "$out/b" --r-count 5 --iterations 50 --tail 10 --no-plot --quiet)
expect_error "r-min" "${b[@]}" --r-min 1.5
expect_error "r-max" "${b[@]}" --r-max 0
expect_error "r-min" "${b[@]}" --r-min nan
expect_error "r-count" "${b[@]}" --r-count 0
expect_error "iterations" "${b[@]}" --iterations 0
expect_error "tail" "${b[@]}" --tail 100
expect_error "grid" "${b[@]}" --grid "1,2,3"
expect_error "grid" "${b[@]}" --grid "nan,1,-1"
expect_error "grid" "${b[@]}" --grid "0,0,0"
expect_error "grid" "${b[@]}" --grid strip:0x3
expect_error "grid" "${b[@]}" --grid "strip:200000x200000"
expect_error "coord" "${b[@]}" --coord psi
expect_error "precision" "${b[@]}" --precision quad
expect_error "precision" "${b[@]}" --precision mpfr:5
expect_error "bins" "${b[@]}" --bins 0
expect_error "overlay" "${b[@]}" --overlay nonsense
expect_error "threads" "${b[@]}" --threads -1
# Every front end's one wording of a thread count (core::require_threads), 0 meaning all cores everywhere.
expect_error "^btob: error: threads: got 1025, expected 0 (all cores) or 1..1024$" "${b[@]}" --threads 1025
expect_error "^btob: error: threads: got -1, expected 0 (all cores) or 1..1024$" explore --threads -1 --no-browser
all_cores=$(mktemp -d)
if ! "$btob" bifurcation --out "$all_cores" --r-count 5 --iterations 50 --tail 10 --no-plot --quiet --threads 0; then
  echo "FAIL: --threads 0 (all cores) refused"; fail=1
fi
rm -rf "$all_cores"
expect_error "r-count" "${b[@]}" --r-count 100000000000
expect_error "attractors: got with float" "${b[@]}" --attractors --precision float
expect_error "attractors: got with double and algorithm trig" "${b[@]}" --attractors --algorithm trig
expect_error "attractors: got with tail = iterations" "${b[@]}" --attractors --tail 50
[ -e "$out/b" ] && [ -n "$(ls -A "$out/b")" ] && { echo "FAIL: output written despite errors: $(ls "$out/b")"; fail=1; }

printf 'command = "bifurcation"\n[args]\nr-mni = 0.1\n' >"$out/bad_key.toml"
expect_error "r-mni" run "$out/bad_key.toml" --out "$out/s"
printf 'command = "bifurcation"\nspeed = 3\n' >"$out/bad_top.toml"
expect_error "speed" run "$out/bad_top.toml" --out "$out/s"
printf 'command = "bifurcation"\n[args\n' >"$out/malformed.toml"
expect_error "malformed.toml" run "$out/malformed.toml" --out "$out/s"
printf 'command = "teleport"\n' >"$out/bad_cmd.toml"
expect_error "teleport" run "$out/bad_cmd.toml" --out "$out/s"
expect_error "scene" run "$out/missing.toml"
[ -e "$out/s" ] && { echo "FAIL: scene output written despite errors"; fail=1; }

# The other subcommands (windows, pattern, lyapunov, precision).
expect_error "n" windows bounds --n 0
expect_error "digits" windows bounds --n 1..3 --digits 5
expect_error "digits" windows bounds --n 1..3 --digits 20000
expect_error "n" windows verify --n 1..3 --out "$out/w"
expect_error "word" pattern 14 --r 0.3
expect_error "word" pattern "" --r 0.3
expect_error "r" pattern 132 --r 1.2
expect_error "charpoly" pattern 1133 --charpoly --r 0.2
expect_error "iterations" lyapunov --r 0.3 --point 1,0.1,-1 --iterations 0
expect_error "transient" lyapunov --r 0.3 --point 1,0.1,-1 --iterations 100 --transient 200
expect_error "r" lyapunov --r 0 --point 1,0.1,-1 --iterations 100 --transient 10
expect_error "point" lyapunov --r 0.3 --point 1,0.1,1 --iterations 100 --transient 10
expect_error "orbits" precision --orbits 0 --out "$out/p"
expect_error "n-max" correlate --r 0.2 --n-max 200 --iterations 200 --out "$out/p"
expect_error "observable" correlate --r 0.2 --observable psi --out "$out/p"
expect_error "bins" measure --r 0.2 --bins 0 --out "$out/p"
expect_error "coords" measure --r 0.2 --coords polar --out "$out/p"
expect_error "r" measure --r 1 --out "$out/p"
expect_error "precision" bifurcation --out "$out/b" --precision mpfr:20000 --no-plot
[ -e "$out/w" ] || [ -e "$out/p" ] && { echo "FAIL: output written despite errors"; fail=1; }

# A good run writes its data and manifest, and an existing result is replaced only by a complete one.
"$btob" "${b[@]}" --name ok || { echo "FAIL: a valid bifurcation run failed"; fail=1; }
for f in ok.h5 ok.json; do [ -s "$out/b/$f" ] || { echo "FAIL: $f missing"; fail=1; }; done
before=$(md5sum "$out/b/ok.h5")
"$btob" "${b[@]}" --name ok --r-min 2 2>/dev/null
[ "$(md5sum "$out/b/ok.h5")" = "$before" ] || { echo "FAIL: a failed run changed an existing result"; fail=1; }
ls "$out/b" | grep -q tmp && { echo "FAIL: temporary files left behind"; fail=1; }

# A full disk, simulated with a file-size limit (RLIMIT_FSIZE: writes past 64 KiB fail with EFBIG; SIGXFSZ
# ignored so the write returns the error instead of killing the process): one line naming the file, exit 1, no
# output folder, no temporary folder left, and an existing result untouched.
full() { (trap '' XFSZ; ulimit -f 64; "$btob" "$@"); }
err=$(full bifurcation --r-count 2000 --iterations 200 --tail 100 --no-plot --quiet --out "$out/full" 2>&1 >/dev/null)
rc=$?
if [ $rc -ne 1 ] || [ "$(printf '%s\n' "$err" | grep -c .)" -ne 1 ] || ! grep -q "bifurcation.h5" <<<"$err"; then
  echo "FAIL (disk full: exit $rc, expected 1 and one line naming the file): $err"; fail=1
else
  echo "ok: disk full -> $err"
fi
[ -e "$out/full" ] && { echo "FAIL: disk full left the output folder"; fail=1; }
ls -a "$out" | grep -q "btob-tmp" && { echo "FAIL: disk full left a temporary folder"; fail=1; }
full bifurcation --r-count 2000 --iterations 200 --tail 100 --no-plot --quiet --out "$out/b" --name ok 2>/dev/null
[ "$(md5sum "$out/b/ok.h5")" = "$before" ] || { echo "FAIL: a run on a full disk changed an existing result"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "cli_errors: all checks passed"; fi
exit $fail
