#!/usr/bin/env bash
# analyze_not_measured_test.sh ANALYZE DUMP WORKDIR
# Numbers shockgas-analyze could not measure are stored as NaN beside a
# <name>_note attribute giving the reason, never as 0 (read back with
# shockgas-dump). WORKDIR holds the fixture's runs: a.h5 (two realizations),
# e05.h5 and e10.h5 (r = 0.9, 0.8), snap1.h5 (one realization, snapshots at
# t = 10 and 1000).
set -u
analyze=$1 dump=$2 work=$3
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# has FILE GROUP LINE-REGEX: the group's attributes include a line matching.
has() {
  "$dump" gnuplot-vars "$1" "$2" --prefix v | grep -Eq -- "$3" || fail "$1 $2 has no line /$3/:
$("$dump" gnuplot-vars "$1" "$2" --prefix v)"
  echo "ok: $1 $2: /$3/"
}
# One realization, and no sparse segment at t = 10: neither the slope nor
# the count's error is 0.
"$analyze" shocks snap1.h5 -o not_measured_shocks.h5 >/dev/null || fail "shocks failed"
has not_measured_shocks.h5 /shocks0 '^v_slope_times_t = NaN$'
has not_measured_shocks.h5 /shocks0 '^v_slope_times_t_note = "no sparse segment'
has not_measured_shocks.h5 /shocks0 '^v_shock_count_sigma = NaN$'
has not_measured_shocks.h5 /shocks0 '^v_shock_count_sigma_note = "one snapshot'
# A fit window shorter than the one-decade windows of the systematic.
"$analyze" decay a.h5 --t-lo 1 --t-hi 5 -o not_measured_decay.h5 >/dev/null || fail "decay failed"
has not_measured_decay.h5 /decay '^v_exponent_window_systematic = NaN$'
has not_measured_decay.h5 /decay '^v_exponent_window_systematic_note = "no one-decade window'
# Power laws through two points: no chi2/dof.
"$analyze" crossover e05.h5 e10.h5 -o not_measured_crossover.h5 >/dev/null || fail "crossover failed"
has not_measured_crossover.h5 /scaling_in_eps '^v_t_stick_chi2_per_dof = NaN$'
has not_measured_crossover.h5 /scaling_in_eps '^v_t_stick_chi2_per_dof_note = "need at least 3 points for chi2'
rm -f not_measured_shocks.h5 not_measured_decay.h5 not_measured_crossover.h5
