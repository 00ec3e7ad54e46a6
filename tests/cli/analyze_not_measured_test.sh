#!/usr/bin/env bash
# analyze_not_measured_test.sh ANALYZE DUMP WORKDIR
# Numbers shockgas-analyze could not measure are stored as NaN beside a
# <name>_note attribute giving the reason, never as 0 (read back with
# shockgas-dump). WORKDIR holds the fixture's runs: a.h5 (two realizations),
# e05.h5 and e10.h5 (r = 0.9, 0.8), snap1.h5 (one realization, snapshots at
# t = 10 and 1000), e10_one.h5 (one realization), hist.h5 (histograms at t = 10
# and 100), short_tail.h5 (a far tail reaching z ~ 3.3), col06.h5 and col_one.h5
# (delta = 0 runs that collapse: three realizations at r = 0.6, one at r = 0.5), col4k.h5
# (three at N = 4000, r = 0.5).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
source "$(dirname "$0")/results_helpers.sh"
analyze=$1 dump=$2 work=$3
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
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
has not_measured_decay.h5 /decay '^v_window_note = "the fit window spans 0.70 decades, under one: .*--t-hi 10 would give a decade"$'
# Power laws through two points: no chi2/dof.
"$analyze" crossover e05.h5 e10.h5 -o not_measured_crossover.h5 >/dev/null || fail "crossover failed"
has not_measured_crossover.h5 /scaling_in_eps '^v_t_stick_chi2_per_dof = NaN$'
has not_measured_crossover.h5 /scaling_in_eps '^v_t_stick_chi2_per_dof_note = "need at least 3 points for chi2'
# A tail fit that ends at the bound 0.5 of its range: gamma and both widths
# are NaN with the bound (hist.h5 at t = 100: 4 tail bins); the collapse's
# distance at the best beta is measured there.
"$analyze" scaling hist.h5 -o not_measured_scaling.h5 >/dev/null || fail "scaling failed"
has not_measured_scaling.h5 /histogram1 '^v_tail_gamma = NaN$'
has not_measured_scaling.h5 /histogram1 '^v_tail_gamma_sigma = NaN$'
has not_measured_scaling.h5 /histogram1 '^v_tail_gamma_note = "at the search bound 0.5 of \[0.5, 8\]'
has not_measured_scaling.h5 /histogram1 '^v_tail_gamma_fit_sigma = NaN$'
has not_measured_scaling.h5 /histogram1 '^v_tail_gamma_fit_sigma_note = "gamma at the search bound 0.5'
# One realization: the decay fit has no weights, so no chi2/dof nor fit width.
"$analyze" decay e10_one.h5 --t-lo 10 --t-hi 1000 -o not_measured_one.h5 >/dev/null || fail "decay (R = 1) failed"
has not_measured_one.h5 /decay '^v_chi2_per_dof = NaN$'
has not_measured_one.h5 /decay '^v_chi2_per_dof_note = "one realization'
has not_measured_one.h5 /decay '^v_exponent_fit_sigma = NaN$'
has not_measured_one.h5 /decay '^v_exponent_fit_sigma_note = "one realization'
# One realization, collapse: its time's sigma and spread are NaN with the reason, and the forms
# against eps, weighted by the inputs' sigmas, are not fitted, their groups naming the input.
"$analyze" collapse col06.h5 col_one.h5 -o not_measured_collapse.h5 >/dev/null || fail "collapse (R = 1) failed"
has not_measured_collapse.h5 /collapse1 '^v_collapse_time_sigma = NaN$'
has not_measured_collapse.h5 /collapse1 '^v_collapse_time_sigma_note = "one realization: the jackknife has nothing'
has not_measured_collapse.h5 /collapse1 '^v_cluster_mass_sigma = NaN$'
has not_measured_collapse.h5 /collapse1 '^v_collapse_time_spread = NaN$'
has not_measured_collapse.h5 /collapse1 '^v_collapse_time_spread_note = "one realization'
has not_measured_collapse.h5 /time_forms '^v_note = "the forms against eps are weighted by each input.s sigma: .col_one.h5. has no'
has not_measured_collapse.h5 /mass_forms '^v_note = "the forms against eps are weighted by each input.s sigma: .col_one.h5. has no'
# Across N the whole first-collapse block is left out, the hazard fit named with it.
"$analyze" collapse col4k.h5 col_one.h5 --vs N -o not_measured_collapse_n.h5 >/dev/null ||
  fail "collapse --vs N (R = 1) failed"
has not_measured_collapse_n.h5 /first_collapse '^v_note = "the fits across N are weighted by each input.s sigma: .col_one.h5. has no error bar .*; the hazard fit, which has sigmas of its own, is left out with them"$'
# far-tail over a window beyond the data: the clipping is stored with the range fitted.
"$analyze" far-tail short_tail.h5 -o not_measured_far_tail.h5 >/dev/null || fail "far-tail failed"
has not_measured_far_tail.h5 /far_tail '^v_window_note = "the window \[2, 5.5\] was clipped to the data: .*fitted over z in \[2.01, '
rm -f not_measured_shocks.h5 not_measured_decay.h5 not_measured_crossover.h5 not_measured_scaling.h5 \
      not_measured_one.h5 not_measured_far_tail.h5 not_measured_collapse.h5 not_measured_collapse_n.h5
