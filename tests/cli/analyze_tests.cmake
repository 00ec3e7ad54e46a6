# SPDX-License-Identifier: GPL-3.0-or-later
# End-to-end tests of shockgas-analyze's answers to bad input and to data that
# do not determine a number: one line "shockgas-analyze: error: <what>", exit
# status 2 and no output file (expect_error.sh), or a number reported as
# "n/a (<reason>)" and stored as NaN with a reason, never nan, inf or 0.
# Included from tests/CMakeLists.txt after cli_tests.cmake.
set(_analyze_dir "${CMAKE_CURRENT_BINARY_DIR}/work/analyze")
file(MAKE_DIRECTORY "${_analyze_dir}")
set(_analyze_program $<TARGET_FILE:shockgas-analyze>)
set(_analyze_expect "${CMAKE_CURRENT_SOURCE_DIR}/cli/expect_error.sh")
set(_analyze_expect_all "${CMAKE_CURRENT_SOURCE_DIR}/cli/analyze_expect_error.sh")

# Small runs (well under a second each), made once for every test below.
foreach(_run IN ITEMS "a|-N;200;-r;0.5;-d;0.01;-t;100;-R;2"
                      "short|-N;200;-r;0.5;-d;0.01;-t;0.9;-R;2"
                      "e05|-N;1000;-r;0.9;-d;0.01;-t;1000;-R;4"
                      "e10|-N;1000;-r;0.8;-d;0.01;-t;1000;-R;4"
                      "e10_one|-N;1000;-r;0.8;-d;0.01;-t;1000;-R;1"
                      "snap1|-N;1000;-r;0.9;-d;0.01;-t;1000;-R;1;--snapshot-times;10,1000"
                      "col|-N;2000;-r;0.5;-d;0;-t;10000;-R;3"
                      "col4k|-N;4000;-r;0.5;-d;0;-t;10000;-R;3"
                      "col06|-N;2000;-r;0.6;-d;0;-t;10000;-R;3"
                      "col300|-N;300;-r;0.5;-d;0;-t;10000;-R;3"
                      "col_one|-N;2000;-r;0.5;-d;0;-t;10000;-R;1"
                      "hist|-N;2000;-r;0.5;-d;0.01;-t;1000;-R;4;--histogram-times;10,100")
  string(FIND "${_run}" "|" _bar)
  string(SUBSTRING "${_run}" 0 ${_bar} _name)
  math(EXPR _start "${_bar} + 1")
  string(SUBSTRING "${_run}" ${_start} -1 _arguments)
  add_test(NAME cli.analyze.setup.${_name}
           COMMAND $<TARGET_FILE:shockgas-sim> ${_arguments} -j 1 -q -o "${_analyze_dir}/${_name}.h5")
  set_tests_properties(cli.analyze.setup.${_name} PROPERTIES FIXTURES_SETUP analyze_cases LABELS cli TIMEOUT 120)
endforeach()

# A far tail that reaches only z ~ 3.3 (shockgas-tail, under a second).
add_test(NAME cli.analyze.setup.short_tail
         COMMAND $<TARGET_FILE:shockgas-tail> -t 100 --half-window 100 --z-reach 2.75 --steps-per-bias 3000
                 --burn-in 500 --chains 3 -j 1 -o "${_analyze_dir}/short_tail.h5")
set_tests_properties(cli.analyze.setup.short_tail PROPERTIES FIXTURES_SETUP analyze_cases LABELS cli TIMEOUT 120)

# shockgas_analyze_error(<name> <regex> <arguments...>): shockgas-analyze with
# the arguments and -o <name>.out.h5 must fail as bad input with one line
# matching regex and leave no <name>.out.h5 (the pattern of shockgas_tool_error
# in cli_tests.cmake; one output name per test, as tests run in parallel). The
# timeout catches a hang (a scan step of 0 would loop forever).
function(shockgas_analyze_error name regex)
  set(_output "${_analyze_dir}/${name}.out.h5")
  add_test(NAME cli.analyze.${name}
           COMMAND ${_analyze_expect} "${regex}" "${_output}" -- ${_analyze_program} ${ARGN} -o "${_output}"
           WORKING_DIRECTORY "${_analyze_dir}")
  set_tests_properties(cli.analyze.${name} PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
endfunction()
# The same, and none of the data files <outputs> (space-separated) may be left either.
function(shockgas_analyze_error_all name regex outputs)
  set(_output "${_analyze_dir}/${name}.out.h5")
  add_test(NAME cli.analyze.${name}
           COMMAND ${_analyze_expect_all} "${regex}" "${_output} ${outputs}" -- ${_analyze_program} ${ARGN}
                   -o "${_output}"
           WORKING_DIRECTORY "${_analyze_dir}")
  set_tests_properties(cli.analyze.${name} PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
endfunction()
# shockgas_analyze_reports(<name> <pass regex> <fail regex> <arguments...>): a run
# that succeeds and prints what it could not measure as n/a, with the reason.
# CTest ignores the exit status when a pass regex is set, so an internal error
# (exit 1) after the n/a line always fails too.
function(shockgas_analyze_reports name pass fail)
  add_test(NAME cli.analyze.${name} COMMAND ${_analyze_program} ${ARGN} WORKING_DIRECTORY "${_analyze_dir}")
  set_tests_properties(cli.analyze.${name} PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60
                       PASS_REGULAR_EXPRESSION "${pass}"
                       FAIL_REGULAR_EXPRESSION "${fail}|shockgas-analyze: internal error")
endfunction()
set(_window --t-lo 1 --t-hi 100)  # a.h5 is too short for the automatic window

# 1. No output over an input, nor two outputs over one file, for any output option.
add_test(NAME cli.analyze.output_is_input
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/analyze_output_is_input_test.sh ${_analyze_program} "${_analyze_dir}")
set_tests_properties(cli.analyze.output_is_input PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)

# 2. The window scan: a step of 0 (which would loop forever) and an empty scan (which would be written with
# status 0) are refused.
foreach(_step IN ITEMS 0 -0.1 1e-9 nan)
  shockgas_analyze_error(scan_step_${_step} "^shockgas-analyze: error: --scan-step must be finite and at least 0.001 decades"
                         decay a.h5 ${_window} --scan-step ${_step})
endforeach()
foreach(_width IN ITEMS -1 0 nan)
  shockgas_analyze_error(scan_width_${_width} "^shockgas-analyze: error: --scan-width \\(in decades\\) must be positive"
                         decay a.h5 ${_window} --scan-width ${_width})
endforeach()
shockgas_analyze_error(scan_width_beyond_data
                       "no window of 50 decades \\(--scan-width\\) with 3 samples lies between t = 1 and 100, in 'a.h5'$"
                       decay a.h5 ${_window} --scan-width 50)

# 3. compare: runs without a common sample time are not in perfect agreement.
shockgas_analyze_error(compare_no_common_time "no sample time in common with the reference run .*, in 'short.h5'$"
                       compare a.h5 short.h5)

# 4. Data files: atomic, checked before any work, a full disk reported as bad input.
shockgas_analyze_error_all(data_not_left_on_failure "never crosses T0/2 .*, in 'short.h5'$"
                           "${_analyze_dir}/c.txt" crossover e05.h5 short.h5 --data c.txt)
shockgas_analyze_error(data_directory_missing "^shockgas-analyze: error: cannot write output '/nonexistent/x.txt'"
                       decay a.h5 ${_window} --data /nonexistent/x.txt)
# Small table: the flush fails; large (a profile of ~700 clusters): a write fails.
shockgas_analyze_error(data_full_disk_small
                       "^shockgas-analyze: error: cannot write data file '/dev/full': No space left on device$"
                       decay a.h5 ${_window} --data /dev/full)
shockgas_analyze_error(data_full_disk_large
                       "^shockgas-analyze: error: cannot write data file '/dev/full': No space left on device$"
                       shocks snap1.h5 --data /dev/full)
# A device is written through, not replaced: the table arrives on standard output.
shockgas_analyze_reports(data_to_standard_output "# decay exponent in moving windows.*decay exponent" "error"
                         decay a.h5 ${_window} -o "${_analyze_dir}/stdout_decay.h5" --scan /dev/stdout)
# The same under a shell's `> file`: /dev/stdout is then that file, and opening it anew ("w") would truncate
# it and write at an offset of its own, so the report would overwrite the table's start. It is written
# through the program's own standard output (sim/io/src/text_file.cpp), the table before the report.
add_test(NAME cli.analyze.data_to_redirected_standard_output
         COMMAND sh -c "\"$1\" decay a.h5 --t-lo 1 --t-hi 100 -o stdout_file_decay.h5 --scan /dev/stdout > stdout_file.txt && cat stdout_file.txt"
                 sh ${_analyze_program} WORKING_DIRECTORY "${_analyze_dir}")
set_tests_properties(cli.analyze.data_to_redirected_standard_output PROPERTIES LABELS cli
                     FIXTURES_REQUIRED analyze_cases TIMEOUT 60
                     PASS_REGULAR_EXPRESSION "^# decay exponent in moving windows[^\n]*\n# shockgas-analyze [^\n]*, from a\\.h5\n# input a\\.h5: shockgas-sim, simulator_sha256 [0-9a-f]+, seed 1\n# t_centre[^\n]*\n# exponent_sigma, chi2_per_dof nan: two realizations[^\n]*\n[0-9].*\ndecay exponent "
                     FAIL_REGULAR_EXPRESSION "error")

# 5. Fits with no slope (one eps, one N) are refused naming the inputs; two points leave no chi2.
shockgas_analyze_error(crossover_one_eps "every input has eps = 0.05 \\('e05.h5', 'e05.h5'\\)"
                       crossover e05.h5 e05.h5)
shockgas_analyze_error(collapse_one_eps "every input has eps = 0.25 \\('col.h5', 'col.h5'\\)"
                       collapse col.h5 col.h5 --vs eps)
shockgas_analyze_error(collapse_one_n "every input has N = 2000 \\('col.h5', 'col.h5'\\)"
                       collapse col.h5 col.h5 --vs N)
# --haff-constant: fit (the default) or derived; anything else is refused by name.
shockgas_analyze_error(haff_constant_unknown "--haff-constant: fitted not in \\{fit,derived\\}"
                       crossover e05.h5 e10.h5 --haff-constant fitted)
shockgas_analyze_reports(crossover_derived_haff_constant "t_stick ~ eps\\^.*the data minus it" "error|nan"
                         crossover e05.h5 e10.h5 --haff-constant derived -o "${_analyze_dir}/derived_crossover.h5")
shockgas_analyze_reports(crossover_two_points "chi2/dof n/a \\(need at least 3 points for chi2, got 2\\)" "nan|inf"
                         crossover e05.h5 e10.h5 -o "${_analyze_dir}/two_points_crossover.h5")
shockgas_analyze_reports(collapse_two_n "<t_collapse> ~ N\\^.* \\(chi2/dof n/a \\(need at least 3 points" "nan|inf"
                         collapse col.h5 col4k.h5 --vs N -o "${_analyze_dir}/two_points_collapse.h5")
shockgas_analyze_reports(collapse_two_eps "power .*chi2/dof n/a \\(need at least 3 points" "nan|inf"
                         collapse col.h5 col06.h5 --vs eps -o "${_analyze_dir}/two_points_forms.h5")

# 6. Numbers not measured are n/a with the reason (printed) and NaN with a note (stored).
shockgas_analyze_reports(shocks_no_segment "t 10: .*segment slope x t = n/a \\(no sparse segment"
                         "nan|0\\.000 \\+- 0\\.000" shocks snap1.h5 -o "${_analyze_dir}/no_segment_shocks.h5")
shockgas_analyze_reports(decay_short_window "\\+- n/a \\(window: no one-decade window .* \\[1, 5\\]\\)"
                         "nan|\\+- 0\\.0000 \\(window\\)" decay a.h5 --t-lo 1 --t-hi 5 -o "${_analyze_dir}/short_window.h5")
# An automatic window under a decade says so in one line, and what run gives one: hist.h5 (N = 2000,
# t_max = 1000) ends at 0.01 N^3/2 = 894, t_lo = 100; with --start-factor 20 --end-factor 1 at t_max.
shockgas_analyze_reports(decay_window_under_a_decade_particles
                         "\nnote: the fit window spans 0\\.95 decades, under one: [^\n]*; a run with N >= 2200 would give the automatic window a decade\n"
                         "nan" decay hist.h5 -o "${_analyze_dir}/under_a_decade_particles.h5")
shockgas_analyze_reports(decay_window_under_a_decade_t_max
                         "\nnote: the fit window spans 0\\.70 decades, under one: [^\n]*; a run with t_max >= 2000 would give the automatic window a decade\n"
                         "nan" decay hist.h5 --start-factor 20 --end-factor 1 -o "${_analyze_dir}/under_a_decade_t_max.h5")
add_test(NAME cli.analyze.not_measured_stored
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/analyze_not_measured_test.sh ${_analyze_program}
                 $<TARGET_FILE:shockgas-dump> "${_analyze_dir}")
set_tests_properties(cli.analyze.not_measured_stored PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
# ...and fig_collapse and fig_crossovers draw from such files: the points, and where the reason is (they
# stopped on gnuplot's "undefined variable" where the fits were n/a).
if(GNUPLOT_EXECUTABLE)
  add_test(NAME cli.analyze.plots_without_fits
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/plots_without_fits_test.sh ${_analyze_program}
                   $<TARGET_FILE:shockgas-dump> ${GNUPLOT_EXECUTABLE} ${PROJECT_SOURCE_DIR}/figures "${_analyze_dir}")
  set_tests_properties(cli.analyze.plots_without_fits PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases
                       TIMEOUT 60 PASS_REGULAR_EXPRESSION "fig_collapse and fig_crossovers drawn where their fits are n/a"
                       FAIL_REGULAR_EXPRESSION "FAIL|undefined")
  # ...and what the figures' keys and titles say (fig4, fig4_sticky, fig_tail, shockgas-look), read from SVG.
  add_test(NAME cli.figure_keys
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/figure_keys_test.sh ${_analyze_program}
                   $<TARGET_FILE:shockgas-dump> ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR} "${_analyze_dir}")
  set_tests_properties(cli.figure_keys PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 120)
endif()

# 7. --hazard: refused where it cannot be written, written for one N.
shockgas_analyze_error_all(hazard_needs_vs_n "^shockgas-analyze: error: --hazard needs --vs N"
                           "${_analyze_dir}/hazard.txt" collapse col.h5 --hazard hazard.txt)
add_test(NAME cli.analyze.hazard_one_n
         COMMAND sh -c "rm -f hazard_one.txt && \"$1\" collapse col.h5 --vs N -o hazard_one.h5 --hazard hazard_one.txt && grep -q '^# N = 2000$' hazard_one.txt"
                 sh ${_analyze_program}
         WORKING_DIRECTORY "${_analyze_dir}")
set_tests_properties(cli.analyze.hazard_one_n PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)

# 8. Option values out of range (NaN included) are refused, naming the option.
foreach(_case IN ITEMS "merge_gap_negative|--merge-gap must be a whole number at least 0, not -1|shocks;snap1.h5;--merge-gap;-1"
                      "jump_fraction_nan|--jump-fraction \\(a multiple of v_rms\\) must be positive and finite, not nan|shocks;snap1.h5;--jump-fraction;nan"
                      "start_factor_negative|--start-factor must be positive and finite, not -1|decay;a.h5;--start-factor;-1"
                      "end_factor_nan|--end-factor must be positive and finite, not nan|decay;a.h5;--end-factor;nan"
                      "t_lo_negative|--t-lo must be positive and finite, not -5|decay;a.h5;--t-lo;-5"
                      "t_hi_below_t_lo|--t-hi \\(10\\) must be larger than --t-lo \\(20\\)|decay;a.h5;--t-lo;20;--t-hi;10"
                      "stick_ratio_one|--stick-ratio must be finite and above 1 \\(T / T_Haff starts at 1 and rises\\), not 1|crossover;e05.h5;--stick-ratio;1"
                      "coarse_grain_nan|--coarse-grain: must be a finite number >= 0, not 'nan'|shocks;snap1.h5;--coarse-grain;nan"
                      "z_hi_below_z_lo|--z-hi must be finite and larger than --z-lo \\(3\\), not 2|far-tail;a.h5;--z-lo;3;--z-hi;2")
  string(REPLACE "|" ";" _parts "${_case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _regex)
  list(SUBLIST _parts 2 -1 _arguments)
  shockgas_analyze_error(${_name} "^shockgas-analyze: error: ${_regex}$" ${_arguments})
endforeach()

# 9b. A misspelt subcommand names the nearest one and all of them (CLI11 alone says "A subcommand is
# required"), through the shared shockgas::cli::parse; -o and its value (added by the helper) are not it.
set(_subcommands "the subcommands are decay, crossover, scaling, shocks, collapse, compare, validity, far-tail, cooling, clusters, late-decay")
shockgas_analyze_error(subcommand_misspelt
                       "^shockgas-analyze: error: unknown subcommand 'scalng' \\(did you mean scaling\\?; ${_subcommands}\\)$"
                       scalng hist.h5)
shockgas_analyze_error(subcommand_unknown
                       "^shockgas-analyze: error: unknown subcommand 'frobnicate' \\(${_subcommands}\\)$"
                       frobnicate hist.h5)
shockgas_analyze_error(subcommand_missing "^shockgas-analyze: error: a subcommand is required \\(${_subcommands}\\)$")

# 10. Messages: the failing input alone; what --data-only needs; the floor actually used.
shockgas_analyze_error(names_the_failing_input
                       "^shockgas-analyze: error: <T> never crosses T0/2 .*, in 'short.h5'$"
                       crossover e05.h5 short.h5)
shockgas_analyze_error(data_only_needs_data "^shockgas-analyze: error: --data-only needs --data FILE"
                       decay a.h5 --data-only)
shockgas_analyze_error(haff_floor_named "fewer than 3 samples with T >= 0.9 T0 \\(--haff-floor\\).*, in 'e05.h5'$"
                       crossover e05.h5 --haff-floor 0.9)

# 11. A fit that ends at a bound of its search range is not a measurement:
# n/a with the bound (tail gamma over [0.5, 8]; 0.500 +- 0.000 before).
shockgas_analyze_reports(tail_gamma_at_search_bound
                         "t=100 +tail gamma n/a \\(at the search bound 0\\.5 of \\[0\\.5, 8\\]"
                         "tail gamma 0\\.500|nan" scaling hist.h5 -o "${_analyze_dir}/bound_scaling.h5")

# 12. Hints name what the user can change. delta > 0: collapse cannot happen
# at all (not "more particles"); an empty window made by --end-factor names it.
shockgas_analyze_error(collapse_with_threshold
                       "0 realizations collapsed: the run has the threshold delta = 0\\.01 > 0.*inelastic collapse cannot happen.*-d 0\\), in 'a\\.h5'$"
                       collapse a.h5)
shockgas_analyze_error(decay_end_factor_named
                       "t_hi = 8\\.94427 .*; --end-factor 0\\.0001 puts .* raise --end-factor \\(default 0\\.01\\).*, in 'hist\\.h5'$"
                       decay hist.h5 --end-factor 0.0001)

# 13. One realization: no weights, so chi2/dof (0.00 before) and the fit width are n/a.
shockgas_analyze_reports(decay_one_realization_chi2
                         "chi2/dof n/a \\(one realization: no standard error of <T>"
                         "chi2/dof 0\\.00|nan" decay e10_one.h5 --t-lo 10 --t-hi 1000 -o "${_analyze_dir}/one_decay.h5")

# 13b. One realization, crossover: the times with sigma n/a, and the powers of eps, weighted by the
# inputs' sigmas, n/a naming the input: the run is analysed, not refused.
shockgas_analyze_reports(crossover_one_realization
                         "eps 0\\.1 +t_dissip [0-9.]+ \\+- n/a \\(one realization: the jackknife has nothing to leave out"
                         "nan|shockgas-analyze: error" crossover e10_one.h5 -o "${_analyze_dir}/one_crossover.h5")
shockgas_analyze_reports(crossover_one_realization_no_fit_over_eps
                         "against eps: n/a \\(the fits over eps are weighted by each input's sigma: 'e10_one\\.h5' has no error bar \\(one realization"
                         "nan|shockgas-analyze: error" crossover e05.h5 e10_one.h5 -o "${_analyze_dir}/one_crossover_eps.h5")

# 13c. One realization, collapse: its time and mass with sigma n/a (and the spread n/a), and the fits
# across inputs, weighted by their sigmas, n/a naming the input, against eps and against N: the run
# is analysed, not refused.
shockgas_analyze_reports(collapse_one_realization
                         "eps 0\\.25 +N 2000 +collapse time [0-9.]+ \\+- n/a \\(one realization: the jackknife has nothing to leave out; run -R 2 or more\\) \\(spread n/a\\), cluster mass [0-9.]+ \\+- n/a \\(one realization.*\\(1/1 collapsed\\)"
                         "nan|shockgas-analyze: error" collapse col_one.h5 -o "${_analyze_dir}/one_collapse.h5")
shockgas_analyze_reports(collapse_one_realization_no_forms_over_eps
                         "forms against eps: n/a \\(the forms against eps are weighted by each input's sigma: 'col_one\\.h5' has no error bar \\(one realization"
                         "nan|shockgas-analyze: error" collapse col06.h5 col_one.h5 -o "${_analyze_dir}/one_collapse_eps.h5")
shockgas_analyze_reports(collapse_one_realization_no_fits_across_n
                         "first-collapse statistics across N: n/a \\(the fits across N are weighted by each input's sigma: 'col_one\\.h5' has no error bar \\(one realization"
                         "nan|shockgas-analyze: error" collapse col4k.h5 col_one.h5 --vs N -o "${_analyze_dir}/one_collapse_n.h5")

# 14. far-tail: a window beyond the data says it was clipped, with the range fitted.
shockgas_analyze_reports(far_tail_window_clipped
                         "note: the window \\[2, 5\\.5\\] was clipped to the data: usable bins end before z_hi, fitted over z in \\[2\\.01, "
                         "nan" far-tail short_tail.h5 -o "${_analyze_dir}/clipped_far_tail.h5")

# 15. shockgas-look: its hint for a run without a fit window names options it
# takes (it passes --t-lo/--t-hi to shockgas-analyze decay), not --data-only.
if(GNUPLOT_EXECUTABLE)
  add_test(NAME cli.analyze.look_hint
           COMMAND ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR}
                   ${PROJECT_SOURCE_DIR}/tools/shockgas-look "${_analyze_dir}/col.h5" -o "${_analyze_dir}/look_col.png")
  set_tests_properties(cli.analyze.look_hint PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60
                       PASS_REGULAR_EXPRESSION "no fit: .*to fit a window of your choice: shockgas-look [^ ]*col\\.h5 --t-lo T --t-hi T"
                       FAIL_REGULAR_EXPRESSION "--data-only|unknown argument")
  add_test(NAME cli.analyze.look_window
           COMMAND ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR}
                   ${PROJECT_SOURCE_DIR}/tools/shockgas-look "${_analyze_dir}/col.h5" -o "${_analyze_dir}/look_window.png"
                   --t-lo 0.1 --t-hi 5)
  set_tests_properties(cli.analyze.look_window PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60
                       PASS_REGULAR_EXPRESSION "decay exponent .*window \\[0\\.1, 5\\]"
                       FAIL_REGULAR_EXPRESSION "unknown argument|error")
  # A window the user chose that cannot be fitted is a mistake: one line, status 2.
  add_test(NAME cli.analyze.look_window_refused
           COMMAND ${_analyze_expect} "^shockgas-look: error: the window \\[50, 100\\] holds 0 sample times"
                   "${_analyze_dir}/look_refused.png" --
                   ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR}
                   ${PROJECT_SOURCE_DIR}/tools/shockgas-look "${_analyze_dir}/col.h5" -o "${_analyze_dir}/look_refused.png"
                   --t-lo 50 --t-hi 100)
  set_tests_properties(cli.analyze.look_window_refused PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
  # Before any work, one line each (not gnuplot's error after the analysis for a missing output
  # directory, nor two contradictory lines for a file that is not a run).
  foreach(_case IN ITEMS
          "output_directory_missing|^shockgas-look: error: cannot write '.*/no_such_directory/look\\.png': directory '.*/no_such_directory' does not exist$|${_analyze_dir}/col.h5|${_analyze_dir}/no_such_directory/look.png"
          "not_a_run|^shockgas-look: error: .*typo\\.toml' is not a readable HDF5 file|${CMAKE_CURRENT_SOURCE_DIR}/cli/typo.toml|${_analyze_dir}/look_not_a_run.png")
    string(REPLACE "|" ";" _case "${_case}")
    list(GET _case 0 _name)
    list(GET _case 1 _regex)
    list(GET _case 2 _input)
    list(GET _case 3 _png)
    add_test(NAME cli.analyze.look_${_name}
             COMMAND ${_analyze_expect} "${_regex}" "${_png}" --
                     ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}/tools/shockgas-look
                     "${_input}" -o "${_png}")
    set_tests_properties(cli.analyze.look_${_name} PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
  endforeach()
endif()

# 16. An interrupted run (Ctrl-C after 2 s: realization 0 of 3 reached the histogram times 1 and 10, 1 and
# 2 never started) and the checkpoint it leaves. scaling must not count the rows of zeros of the realizations
# that never reached a histogram time as realizations (means, errors, the tail fit would all be wrong): each
# time uses the realizations that reached it, and says so.
add_test(NAME cli.analyze.setup.interrupted
         COMMAND bash -c "rm -f interrupted.h5 interrupted.h5.checkpoint interrupted.h5.checkpoint.previous; timeout -s INT 2 \"$0\" -N 100 -r 0.5 -d 0.01 -t 1e300 -R 3 -q -j 1 --histogram-times 1,10 -o interrupted.h5 2>/dev/null; test -e interrupted.h5 && test -e interrupted.h5.checkpoint"
                 $<TARGET_FILE:shockgas-sim>
         WORKING_DIRECTORY "${_analyze_dir}")
set_tests_properties(cli.analyze.setup.interrupted PROPERTIES FIXTURES_SETUP analyze_cases LABELS cli TIMEOUT 120)
shockgas_analyze_reports(scaling_interrupted_uses_reached
                         "note: t = 1 in 'interrupted.h5': 1 of 3 realizations reached it; the estimates at this time use only these \\(the run was interrupted: shockgas-sim --resume"
                         "nan|error" scaling interrupted.h5 -o "${_analyze_dir}/interrupted_scaling.h5")
shockgas_analyze_error(decay_interrupted_names_resume
                       "no sample time t > 0 was reached with T > 0 by every realization: the run was interrupted; continue it with shockgas-sim --resume and the same options, in 'interrupted.h5'$"
                       decay interrupted.h5)
# 17. Every subcommand refuses a checkpoint (decay and compare would print results from one), in one check.
# shockgas_analyze_refused_by(<prefix> <file> <regex> <case>...): the test cli.analyze.<prefix>_<name> for
# each case "name|subcommand[|arguments]", run on <file>, must fail with <regex>.
set(_every_subcommand "decay|decay" "crossover|crossover" "scaling|scaling" "shocks|shocks" "collapse|collapse"
                      "far_tail|far-tail" "compare|compare|a.h5")
function(shockgas_analyze_refused_by prefix file regex)
  foreach(_case IN LISTS ARGN)
    string(REPLACE "|" ";" _parts "${_case}")
    list(GET _parts 0 _name)
    list(SUBLIST _parts 1 -1 _arguments)
    shockgas_analyze_error(${prefix}_${_name} "${regex}" ${_arguments} ${file})
  endforeach()
endfunction()
shockgas_analyze_refused_by(checkpoint_refused interrupted.h5.checkpoint
  "^shockgas-analyze: error: 'interrupted\\.h5\\.checkpoint' is a shockgas-sim checkpoint \\(a run in progress\\), not an output: continue the run with shockgas-sim --resume and the same options$"
  ${_every_subcommand})
# 17b. A file that is not a run is named for what it is, in one line, by every subcommand: an analysis
# results file before any work (not as "missing attribute /restitution in 'dec.h5'"), and a far-tail
# file where the run is read (not as "missing group /timeseries"; crossover and scaling: where they
# read its restitution, run_parameters). far-tail reads the far-tail file, so it is not in the second
# list.
add_test(NAME cli.analyze.setup.results_input
         COMMAND $<TARGET_FILE:shockgas-analyze> decay a.h5 ${_window} -o results_input.h5
         WORKING_DIRECTORY "${_analyze_dir}")
set_tests_properties(cli.analyze.setup.results_input PROPERTIES FIXTURES_REQUIRED analyze_cases
                     FIXTURES_SETUP analyze_results_input LABELS cli)
set(_every_subcommand_of_a_run ${_every_subcommand})
list(REMOVE_ITEM _every_subcommand_of_a_run "far_tail|far-tail")
shockgas_analyze_refused_by(results_refused results_input.h5
  "^shockgas-analyze: error: 'results_input\\.h5' is not a shockgas-sim output: it is an analysis results file \\(made by shockgas-analyze decay\\)$"
  ${_every_subcommand_of_a_run})
# far-tail reads a shockgas-tail file, and says so (not "not a shockgas-sim output").
shockgas_analyze_refused_by(results_refused results_input.h5
  "^shockgas-analyze: error: 'results_input\\.h5' is not a far-tail sampler file \\(made by shockgas-tail\\): it is an analysis results file \\(made by shockgas-analyze decay\\)$"
  "far_tail|far-tail")
foreach(_case IN LISTS _every_subcommand)
  string(REGEX REPLACE "\\|.*" "" _name "${_case}")
  set_tests_properties(cli.analyze.results_refused_${_name} PROPERTIES FIXTURES_REQUIRED "analyze_cases;analyze_results_input")
endforeach()
shockgas_analyze_refused_by(tail_refused short_tail.h5
  "^shockgas-analyze: error: 'short_tail\\.h5' is not a shockgas-sim output: it is a far-tail sampler file \\(made by shockgas-tail; shockgas-analyze far-tail reads it\\)$"
  ${_every_subcommand_of_a_run})
# 18. compare takes runs that differ in delta and the sub-threshold rule only: another N, r or seed is refused,
# naming each difference (the run's value first); a run of another delta is compared.
shockgas_analyze_error(compare_other_restitution
                       "^shockgas-analyze: error: 'e10\\.h5' is not comparable with the reference 'e05\\.h5': restitution 0\\.8 vs 0\\.9 \\(compare takes"
                       compare e05.h5 e10.h5)
shockgas_analyze_error(compare_other_particles
                       "^shockgas-analyze: error: 'e05\\.h5' is not comparable with the reference 'a\\.h5': particles 1000 vs 200, ring_length 1000 vs 200, restitution 0\\.9 vs 0\\.5 \\("
                       compare a.h5 e05.h5)
add_test(NAME cli.analyze.setup.a_seed
         COMMAND $<TARGET_FILE:shockgas-sim> -N 200 -r 0.5 -d 0.01 -t 100 -R 2 -s 7 -j 1 -q -o "${_analyze_dir}/a_seed.h5")
add_test(NAME cli.analyze.setup.a_sticky
         COMMAND $<TARGET_FILE:shockgas-sim> -N 200 -r 0.5 -d 0.02 --subthreshold sticky -t 100 -R 2 -j 1 -q
                 -o "${_analyze_dir}/a_sticky.h5")
set_tests_properties(cli.analyze.setup.a_seed cli.analyze.setup.a_sticky PROPERTIES FIXTURES_SETUP analyze_cases
                     LABELS cli TIMEOUT 120)
shockgas_analyze_error(compare_other_seed
                       "^shockgas-analyze: error: 'a_seed\\.h5' is not comparable with the reference 'a\\.h5': seed 7 vs [0-9]+ \\("
                       compare a.h5 a_seed.h5)
shockgas_analyze_reports(compare_other_threshold "a_sticky\\.h5 +delta 0\\.02 +sticky" "error"
                         compare a.h5 a_sticky.h5 -o "${_analyze_dir}/other_threshold_compare.h5")
# 19. The results file records how it was made: the command line and every option of the subcommand.
add_test(NAME cli.analyze.options_recorded
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/analyze_options_recorded_test.sh ${_analyze_program}
                 $<TARGET_FILE:shockgas-dump> "${_analyze_dir}")
set_tests_properties(cli.analyze.options_recorded PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_cases TIMEOUT 60)
