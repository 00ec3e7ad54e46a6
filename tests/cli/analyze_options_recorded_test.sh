#!/usr/bin/env bash
# analyze_options_recorded_test.sh ANALYZE DUMP WORKDIR
# A results file says how it was made: the root attribute command_line and,
# in /options, every option of the subcommand with the value it ran with
# (defaults included; --t-lo only when given; not --help or --help-all,
# which print and exit), so that files of other options differ in their
# attributes (shocks with --jump-fraction 2 and with the default give 104 and
# 416 shocks). Also: scaling on an interrupted run stores how many
# realizations each histogram time used. WORKDIR holds the fixture's runs
# (snap1.h5, a.h5, hist.h5, interrupted.h5; tests/cli/analyze_tests.cmake).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
source "$(dirname "$0")/results_helpers.sh"
analyze=$1 dump=$2 work=$3
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$analyze" shocks snap1.h5 -o options_default.h5 >/dev/null || fail "shocks failed"
"$analyze" shocks snap1.h5 --jump-fraction 2 --merge-gap 3 -o options_jump.h5 >/dev/null || fail "shocks --jump-fraction 2 failed"
has options_default.h5 /options '^v_jump_fraction = 1$'
has options_default.h5 /options '^v_merge_gap = 2$'  # the default (analysis/README.md, Shocks)
has options_default.h5 /options '^v_segment_break = 0.1$'
has options_default.h5 /options '^v_coarse_grain = 0$'
# Only options of the run: not the flags that print and exit (--help-all, inherited by every subcommand).
lacks options_default.h5 /options '^v_help'
has options_jump.h5 /options '^v_jump_fraction = 2$'
has options_jump.h5 /options '^v_merge_gap = 3$'
has options_jump.h5 / '^v_command_line = ".*shockgas-analyze shocks snap1.h5 --jump-fraction 2 --merge-gap 3 -o options_jump.h5"$'
has options_jump.h5 / '^v_program = "shockgas-analyze shocks"$'
# decay: the window given, the rule's factors; a flag as true/false; an argument with a space quoted.
"$analyze" decay a.h5 --t-lo 1 --t-hi 100 -o 'options decay.h5' >/dev/null || fail "decay failed"
has 'options decay.h5' /options '^v_t_lo = 1$'
has 'options decay.h5' /options '^v_t_hi = 100$'
has 'options decay.h5' /options '^v_start_factor = 10$'
has 'options decay.h5' /options '^v_end_factor = 0.01$'
has 'options decay.h5' /options '^v_scan_width = 1$'
has 'options decay.h5' /options '^v_data_only = "false"$'
has 'options decay.h5' / "^v_command_line = \".* decay a.h5 --t-lo 1 --t-hi 100 -o 'options decay.h5'\"$"
"$analyze" decay hist.h5 --t-hi 1000 -o options_auto.h5 >/dev/null || fail "decay (automatic start) failed"
lacks options_auto.h5 /options '^v_t_lo '
has options_auto.h5 /options '^v_t_hi = 1000$'
has options_auto.h5 /options '^v_output = "options_auto.h5"$'
"$analyze" scaling interrupted.h5 --tail-start 2 -o options_scaling.h5 >/dev/null 2>&1 || fail "scaling failed"
has options_scaling.h5 /options '^v_tail_start = 2$'
has options_scaling.h5 /options '^v_tail_max_error = 0.3$'
has options_scaling.h5 /histogram0 '^v_realizations = 1$'
has options_scaling.h5 /histogram0 '^v_recorded_realizations = 3$'
has options_scaling.h5 /histogram0 '^v_realizations_note = "1 of 3 realizations reached it'
rm -f options_default.h5 options_jump.h5 'options decay.h5' options_auto.h5 options_scaling.h5
echo "PASS"
