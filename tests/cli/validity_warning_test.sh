#!/usr/bin/env bash
# validity_warning_test.sh SIM MAP WORK PYTHON COMPARE_OUTPUTS
# shockgas-sim's warning from the validity map (MAP: the cli tests' hand-made
# map, where T at r = 0.9, delta = 0.01, elastic leaves the sticky gas by 1 %
# at t* = 300):
#   1. a run to t_max = 1000 prints one warning line before its result line;
#   2. the same run without a map (--validity-map '') prints none, and its
#      datasets are bit for bit those of the warned run: the warning changes
#      nothing a run computes;
#   3. a run to t_max = 200, within the measured validity, prints none;
#   4. the map named by SHOCKGAS_VALIDITY_MAP, the default's override, warns as --validity-map does.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
sim=$1 map=$2 work=$3 python=$4 compare=$5
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot make $work"
# N = 100 and one realization: well under a second.
run=(-N 100 -r 0.9 -d 0.01 --subthreshold elastic -R 1 -s 3 -q)
warning='^shockgas-sim: warning: t_max = 1000 lies past the measured validity of T for r = 0.9, delta = 0.01 \(elastic\): T leaves the sticky gas by 1 % at t\* .* 300 \(test map, shockgas fixture; docs/validity.md\)$'

"$sim" "${run[@]}" -t 1000 --validity-map "$map" -o "$work/warned.h5" 2>"$work/warned.err" || fail "the warned run: $(cat "$work/warned.err")"
[ "$(grep -c '^shockgas-sim: warning:' "$work/warned.err")" = 1 ] || fail "expected one warning line: $(cat "$work/warned.err")"
grep -Eq "$warning" "$work/warned.err" || fail "the warning line: $(cat "$work/warned.err")"
[ "$(head -n 1 "$work/warned.err" | grep -c '^shockgas-sim: warning:')" = 1 ] || fail "the warning is not first: $(cat "$work/warned.err")"

"$sim" "${run[@]}" -t 1000 --validity-map '' -o "$work/plain.h5" 2>"$work/plain.err" || fail "the run without a map"
grep -q '^shockgas-sim: warning:' "$work/plain.err" && fail "--validity-map '' warned: $(cat "$work/plain.err")"
"$python" "$compare" "$work/warned.h5" "$work/plain.h5" || fail "the warned run's file differs from the plain one's"

"$sim" "${run[@]}" -t 200 --validity-map "$map" -o "$work/within.h5" 2>"$work/within.err" || fail "the run within validity"
grep -q '^shockgas-sim: warning:' "$work/within.err" && fail "a run within the measured validity warned: $(cat "$work/within.err")"

SHOCKGAS_VALIDITY_MAP="$map" "$sim" "${run[@]}" -t 1000 -o "$work/default.h5" 2>"$work/default.err" ||
  fail "the run with SHOCKGAS_VALIDITY_MAP"
grep -Eq "$warning" "$work/default.err" || fail "SHOCKGAS_VALIDITY_MAP's map gave no warning: $(cat "$work/default.err")"
echo "ok: warned past t* = 300, silent within it and without a map, datasets identical"
