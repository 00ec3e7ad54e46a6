#!/usr/bin/env bash
# burgers_provenance_test.sh BURGERS RUN.h5 WORKDIR
# shockgas-burgers' text outputs (the profile, --summary, --study) begin with
# '#' lines naming the program's version, the date (UTC) and the start: the
# seed, realization and law of a drawn start, or the run and its realization,
# so that two profiles of other seeds can be told apart. RUN.h5: -N 400, seed 1, realizations 3 and 4 drawn
# (--first-realization 3), Gaussian velocities, a snapshot at t = 20.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
burgers=$1 run=$2 work=$3
mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
version=$("$burgers" --version) || fail "--version failed"
version=${version#shockgas-burgers }
date_line='^# date [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z$'
"$burgers" -N 100 -s 7 --realization 2 -t 10 -o drawn.dat --summary drawn.gp --study drawn_study.dat >/dev/null ||
    fail "a drawn start failed"
for file in drawn.dat drawn.gp drawn_study.dat; do
    [ "$(sed -n 1p "$file")" = "# shockgas-burgers $version, from seed 7 realization 2 (positions lattice, velocities uniform, as shockgas-sim draws them)" ] ||
        fail "$file: first line '$(sed -n 1p "$file")'"
    sed -n 2p "$file" | grep -Eq "$date_line" || fail "$file: second line '$(sed -n 2p "$file")' is not the date"
done
"$burgers" --run "$run" --realization 1 -o run.dat >/dev/null || fail "--run failed"
[ "$(sed -n 1p run.dat)" = "# shockgas-burgers $version, from run '$run' realization 1 (drawn as realization 4 of seed 1, positions lattice, velocities gaussian)" ] ||
    fail "run.dat: first line '$(sed -n 1p run.dat)'"
# The profile's own header follows, unchanged.
sed -n 3p run.dat | grep -q '^# Burgers profile at t = 20: N = 400' || fail "run.dat: third line '$(sed -n 3p run.dat)'"
echo "ok"
