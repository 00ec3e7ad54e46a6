# SPDX-License-Identifier: GPL-3.0-or-later
# End-to-end tests of shockgas-sim: every bad input gives one line naming the
# problem, a nonzero exit status and no output file; good runs write files
# with the right status.
set(_cli_dir "${CMAKE_CURRENT_BINARY_DIR}/work/cli")
file(MAKE_DIRECTORY "${_cli_dir}")
set(_sim $<TARGET_FILE:shockgas-sim>)
set(_expect "${CMAKE_CURRENT_SOURCE_DIR}/cli/expect_error.sh")

function(shockgas_cli_error name regex)
  add_test(NAME cli.error.${name}
           COMMAND ${_expect} "${regex}" "${_cli_dir}/${name}.h5" -- ${_sim} ${ARGN} -o "${_cli_dir}/${name}.h5"
           WORKING_DIRECTORY "${_cli_dir}")
  set_tests_properties(cli.error.${name} PROPERTIES LABELS cli)
endfunction()

# One bad-input case of another program, "name;regex;arguments...", as the test
# cli.error.<prefix>_<name>: ARGN (the program and its fixed arguments), then the
# case's arguments and -o <prefix>_<name>.out.h5, which must not be written.
function(shockgas_error_case prefix case)
  list(GET case 0 _name)
  list(GET case 1 _regex)
  list(SUBLIST case 2 -1 _arguments)
  set(_output "${_cli_dir}/${prefix}_${_name}.out.h5")
  add_test(NAME cli.error.${prefix}_${_name}
           COMMAND ${_expect} "${_regex}" "${_output}" -- ${ARGN} ${_arguments} -o "${_output}"
           WORKING_DIRECTORY "${_cli_dir}")
  set_tests_properties(cli.error.${prefix}_${_name} PROPERTIES LABELS cli)
endfunction()

# shockgas-burgers' refusal of its arguments (ARGN) as the test cli.error.burgers_<name>: one line
# matching regex, status 2, and no profile -o burgers_<name>.dat; fixture: the run or file it reads.
function(shockgas_burgers_error name fixture regex)
  set(_output "${_cli_dir}/burgers_${name}.dat")
  add_test(NAME cli.error.burgers_${name}
           COMMAND ${_expect} "${regex}" "${_output}" -- $<TARGET_FILE:shockgas-burgers> ${ARGN} -o "${_output}")
  set_tests_properties(cli.error.burgers_${name} PROPERTIES FIXTURES_REQUIRED ${fixture} LABELS cli)
endfunction()

# The far-tail sampler follows the same rule (status 2, one line, no file).
foreach(_case IN ITEMS "threads_negative;threads must be >= 0;-j;-1" "one_chain;need >= 2 chains;--chains;1"
                      "block_probability;block probability must lie in;--block-probability;1.5"
                      "focus_probability;focus probability must lie in;--focus-probability;2"
                      "exchange_zero;exchange interval must be;--exchange-interval;0"
                      "bias_infinite;biases must be finite;--biases;0;inf"
                      "focus_negative;--focus must be;--focus=-1"
                      "bin_width_off_grid;multiple of the;--bin-width;0.0215"
                      "seed_negative;--seed: must be an integer from 0 to 2\\^63 - 1;--seed;-1"
                      "progress_interval_nan;--progress-interval: must be a finite number >= 0, not 'nan';--progress-interval;nan")
  shockgas_error_case(tail "${_case}" $<TARGET_FILE:shockgas-tail> -t 10 --half-window 20 --steps-per-bias 10
                      --burn-in 0)
endforeach()
# Named by its own option, not as "need >= 1 step per bias".
shockgas_error_case(tail "burn_in_negative;--burn-in must be >= 0;--burn-in=-3" $<TARGET_FILE:shockgas-tail> -t 10
                    --half-window 20 --steps-per-bias 10)
add_test(NAME cli.error.tail_half_window_huge
         COMMAND ${_expect} "half window must hold at most 1000000 particles" "${_cli_dir}/tail_half_window_huge.h5" --
                 $<TARGET_FILE:shockgas-tail> -t 10 --half-window 100000000 -o "${_cli_dir}/tail_half_window_huge.h5"
         WORKING_DIRECTORY "${_cli_dir}")
set_tests_properties(cli.error.tail_half_window_huge PROPERTIES LABELS cli)
# Every option of shockgas-tail --help says what it does, --focus-probability, --z-min and --z-max
# among them.
foreach(_case IN ITEMS "focus_probability|share of proposals whose site" "z_min|lower end of the z range"
                      "z_max|upper end of the z range")
  string(REPLACE "|" ";" _case "${_case}")
  list(GET _case 0 _name)
  list(GET _case 1 _words)
  add_test(NAME cli.tail_help_${_name} COMMAND $<TARGET_FILE:shockgas-tail> --help)
  set_tests_properties(cli.tail_help_${_name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "${_words}")
endforeach()
# shockgas-burgers: the same rule, NaN included.
foreach(_case IN ITEMS "time_nan;^shockgas-burgers: error: --time must be positive and finite, not nan$;-N;100;-t;nan"
                      "cells_zero;--cells-per-particle must be at least 1;-N;100;-t;10;--cells-per-particle;0"
                      "viscosity_negative;--viscosity must be positive and finite;-N;100;-t;10;--viscosity;0.1,-1"
                      "one_particle;give --run, --init or --particles \\(at least 2\\);-N;1;-t;10"
                      "seed_beyond_64_bits;--seed: must be an integer from 0 to 2\\^63 - 1;-N;100;-t;1;-s;18446744073709551616"
                      "study_full_disk;^shockgas-burgers: error: cannot write '/dev/full': No space left on device$;-N;100;-t;1;--study;/dev/full"
                      # Refused at once: the first would run out of memory after 20 s (std::bad_alloc), the
                      # second would print the summary, then lose the profile under it.
                      "memory;^shockgas-burgers: error: not enough memory: N = 2000000000 needs about .* GiB, but .* may be used;-N;2000000000;-t;1"
                      "summary_is_output;^shockgas-burgers: error: -o and --summary name the same file;-N;100;-t;1;--summary;${_cli_dir}/burgers_summary_is_output.out.h5")
  shockgas_error_case(burgers "${_case}" $<TARGET_FILE:shockgas-burgers>)
endforeach()
# shockgas-burgers --run rebuilds the run's own start (its velocity law, and the
# realization number of a part made with --first-realization) and, for the sticky
# gas at one cell per particle, agrees with it exactly: every cluster moves with its
# Burgers shock's velocity, so the velocity misfit is rounding (3e-16; 1.4 v_rms
# when clusters are compared with one side of the jump, O(1) from the paper's
# uniform start drawn in place of the run's Gaussian one).
add_test(NAME cli.setup.burgers_sticky_run
         COMMAND ${_sim} -N 400 -r 0 -d 0 -t 20 --snapshot-times 20 -R 2 --first-realization 3
                 --velocity-distribution gaussian -q -o "${_cli_dir}/burgers_sticky.h5")
set_tests_properties(cli.setup.burgers_sticky_run PROPERTIES FIXTURES_SETUP burgers_sticky LABELS cli)
add_test(NAME cli.burgers_sticky_identity
         COMMAND $<TARGET_FILE:shockgas-burgers> --run "${_cli_dir}/burgers_sticky.h5" --realization 1
                 --cells-per-particle 1 -o "${_cli_dir}/burgers_sticky.dat")
set_tests_properties(cli.burgers_sticky_identity PROPERTIES FIXTURES_REQUIRED burgers_sticky LABELS cli
                     PASS_REGULAR_EXPRESSION "v_Burgers\\| / v_rms = (0|[0-9.]+e-(1[3-9]|[2-9][0-9]))\n")
# --run takes the start from the run, so --init beside it is refused, naming both (not as a missing
# dataset /position, even when both name the same file).
add_test(NAME cli.error.burgers_run_and_init
         COMMAND ${_expect}
                 "^shockgas-burgers: error: --run '[^']*burgers_sticky\\.h5' and --init '[^']*burgers_sticky\\.h5' exclude each other: --run takes the initial condition from the run"
                 "${_cli_dir}/burgers_run_and_init.dat" --
                 $<TARGET_FILE:shockgas-burgers> --run "${_cli_dir}/burgers_sticky.h5" --init "${_cli_dir}/burgers_sticky.h5"
                 -o "${_cli_dir}/burgers_run_and_init.dat")
set_tests_properties(cli.error.burgers_run_and_init PROPERTIES FIXTURES_REQUIRED burgers_sticky LABELS cli)
# Likewise -N, -L and -s, which the run supplies too: refused, not ignored (the profile is the
# run's, whatever they say). Refused as --init is, by one exclusion (cli::exclude).
foreach(_case IN ITEMS "particles|--particles '500'|-N;500" "ring_length|--ring-length '800'|-L;800"
                      "seed|--seed '7'|-s;7")
  string(REPLACE "|" ";" _case "${_case}")
  list(GET _case 0 _name)
  list(GET _case 1 _given)
  list(SUBLIST _case 2 -1 _arguments)
  shockgas_burgers_error(run_and_${_name} burgers_sticky
    "^shockgas-burgers: error: --run '[^']*burgers_sticky\\.h5' and ${_given} exclude each other: --run takes the initial condition from the run \\(its N, L, seed and law, or its init file\\); give one of them$"
    --run "${_cli_dir}/burgers_sticky.h5" ${_arguments})
endforeach()
# --init's file is the start itself: -N (like -L, -s and --realization) beside it is refused as well, not
# ignored.
shockgas_burgers_error(init_and_particles burgers_sticky
  "^shockgas-burgers: error: --init '[^']*burgers_sticky\\.h5' and --particles '500' exclude each other: --init's file is the initial condition itself \\(its N, L and velocities\\); give one of them$"
  --init "${_cli_dir}/burgers_sticky.h5" -N 500)
# The profile is built on the lattice of the particles' start: a run made with --positions uniform
# is refused in one line naming the file, the first particle off the lattice and what is needed (not
# only "burgers: particles are not equally spaced (particle 1)").
add_test(NAME cli.setup.burgers_uniform_run
         COMMAND ${_sim} -N 100 --positions uniform -t 10 --snapshot-times 10 -q -o "${_cli_dir}/burgers_uniform.h5")
set_tests_properties(cli.setup.burgers_uniform_run PROPERTIES FIXTURES_SETUP burgers_uniform LABELS cli)
shockgas_burgers_error(off_lattice_run burgers_uniform
  "^shockgas-burgers: error: '[^']*burgers_uniform\\.h5' starts from particles that are not equally spaced \\(particle [0-9]+ is off the lattice x_0 \\+ i L/N\\): the Burgers profile is built on the lattice of the particles' start, so it needs equally spaced particles, as shockgas-sim --positions lattice \\(the default\\) places them$"
  --run "${_cli_dir}/burgers_uniform.h5")
# Every text output begins with the version, the date and the start (seed, realization and law, or
# the run or init file), so that two profiles of other seeds can be told apart.
add_test(NAME cli.burgers_provenance
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/burgers_provenance_test.sh $<TARGET_FILE:shockgas-burgers>
                 "${_cli_dir}/burgers_sticky.h5" "${_cli_dir}/burgers_provenance")
set_tests_properties(cli.burgers_provenance PROPERTIES FIXTURES_REQUIRED burgers_sticky LABELS cli)
shockgas_cli_error(restitution_above_one "restitution" -N 10 -r 1.5)
shockgas_cli_error(restitution_negative "restitution" -N 10 -r -0.1)
shockgas_cli_error(threshold_negative "threshold" -N 10 -d -1e-3)
# Setting another run's checkpoint aside is a way of resuming: alone it is refused.
shockgas_cli_error(set_aside_without_resume "--set-aside-other-runs requires --resume" -N 10 --set-aside-other-runs)
shockgas_cli_error(too_few_particles "particles N must be at least 2" -N 1)
shockgas_cli_error(t_max_zero "t_max" -N 10 -t 0)
shockgas_cli_error(t_max_negative "t_max" -N 10 -t -5)
shockgas_cli_error(bad_subthreshold "sub-threshold" -N 10 --subthreshold gooey)
shockgas_cli_error(sample_beyond_t_max "beyond t_max" -N 10 -t 10 --snapshot-times 20)
shockgas_cli_error(bad_positions "positions must be 'lattice' or 'uniform'" -N 10 --positions random)
shockgas_cli_error(bad_velocity_law "velocity distribution must be" -N 10 --velocity-distribution normal)
shockgas_cli_error(init_missing_file "does not exist" --init "${_cli_dir}/no_such_file.h5")
# The scales double precision must resolve (docs/reliability.md, "Scales and shifts"): one line
# naming the limit and the way out (the model is scale-invariant).
shockgas_cli_error(spacing_below_normal
                   "^shockgas-sim: error: ring length L = 1e-306 gives a spacing L/N = 1e-309, below the smallest normal double 2.23e-308, where gaps lose significant bits; the model is scale-invariant \\(x -> lambda x, t -> lambda t\\): give L at least 2.23e-305 and scale t_max with it$"
                   -N 1000 --ring-length 1e-306 -t 1e-300)
shockgas_cli_error(ring_length_beyond_coordinates "ring length L = 1e\\+308 is beyond 1.12e\\+307 \\(2\\^1020\\)"
                   -N 1000 --ring-length 1e308 -t 1e300)
shockgas_cli_error(t_max_beyond_coordinates "t_max = 1e\\+307 is beyond 2.81e\\+306 \\(2\\^1018\\)" -N 10 -t 1e307)
# Realization F + k past 2^63 - 1 is refused.
shockgas_cli_error(first_realization_overflow "first realization 9223372036854775807 with 3 realizations runs past"
                   -N 10 -t 1 -R 3 --first-realization 9223372036854775807)
# More realizations than an int holds: named with the range and the way out (CLI11 alone says only
# "Could not convert").
shockgas_cli_error(realizations_beyond_int
                   "^shockgas-sim: error: --realizations: must be an integer from 1 to 2\\^31 - 1 = 2147483647, not '1000000000000' \\(a larger ensemble runs as parts: --first-realization, then shockgas-merge\\)$"
                   -N 10 -t 1 -R 1e12)
add_test(NAME cli.error.unwritable_output
         COMMAND ${_expect} "directory .* does not exist" "${_cli_dir}/absent_dir/out.h5" --
                 ${_sim} -N 10 -o "${_cli_dir}/absent_dir/out.h5")
set_tests_properties(cli.error.unwritable_output PROPERTIES LABELS cli)

# Typos: the nearest option or config key is named.
shockgas_cli_error(option_typo "unknown option '--restituion' \\(did you mean --restitution\\?\\)"
                   -N 10 --restituion 0.5)
shockgas_cli_error(config_typo "unknown option 'threshhold' in .*typo.toml \\(did you mean threshold\\?\\)"
                   --config "${CMAKE_CURRENT_SOURCE_DIR}/cli/typo.toml")

# shockgas-analyze and shockgas-merge: the same one-line form and exit status 2.
set(_analyze $<TARGET_FILE:shockgas-analyze>)
function(shockgas_tool_error name regex)
  add_test(NAME cli.error.${name}
           COMMAND ${_expect} "${regex}" "${_cli_dir}/${name}.out.h5" -- ${ARGN}
           WORKING_DIRECTORY "${_cli_dir}")
  set_tests_properties(cli.error.${name} PROPERTIES LABELS cli)
endfunction()
add_test(NAME cli.setup.one_realization COMMAND ${_sim} -N 1000 -t 1000 -R 1 -q -o "${_cli_dir}/one_realization.h5")
add_test(NAME cli.setup.collapsed COMMAND ${_sim} -N 2000 -r 0.5 -d 0 -t 10000 -R 2 -q -o "${_cli_dir}/collapsed.h5")
add_test(NAME cli.setup.other_restitution
         COMMAND ${_sim} -N 1000 -t 1000 -R 1 -r 0.5 --first-realization 1 -q -o "${_cli_dir}/other_restitution.h5")
set_tests_properties(cli.setup.one_realization cli.setup.collapsed cli.setup.other_restitution PROPERTIES
                     FIXTURES_SETUP analyze_inputs LABELS cli)
shockgas_tool_error(analyze_missing_file "^shockgas-analyze: error: .*does not exist.*no_such.h5"
                    ${_analyze} decay "${_cli_dir}/no_such.h5" -o "${_cli_dir}/analyze_missing_file.out.h5")
shockgas_tool_error(analyze_unwritable "^shockgas-analyze: error: cannot write output '.*absent_dir/a.h5'"
                    ${_analyze} decay "${_cli_dir}/one_realization.h5" -o "${_cli_dir}/absent_dir/a.h5")
shockgas_tool_error(analyze_collapsed "inelastic collapse.*--data-only.*, in '.*collapsed.h5'"
                    ${_analyze} decay "${_cli_dir}/collapsed.h5" -o "${_cli_dir}/analyze_collapsed.out.h5")
shockgas_tool_error(analyze_no_snapshots "^shockgas-analyze: error: no /snapshots .*, in '.*one_realization.h5'"
                    ${_analyze} shocks "${_cli_dir}/one_realization.h5" -o "${_cli_dir}/analyze_no_snapshots.out.h5")
shockgas_tool_error(analyze_option_typo "did you mean --t-lo"
                    ${_analyze} decay "${_cli_dir}/one_realization.h5" --t-low 20)
shockgas_tool_error(merge_names_parameter "different parameters .*: restitution 0.5 vs 0.9$"
                    $<TARGET_FILE:shockgas-merge> -o "${_cli_dir}/merge_names_parameter.out.h5"
                    "${_cli_dir}/one_realization.h5" "${_cli_dir}/other_restitution.h5")
set_tests_properties(cli.error.analyze_unwritable cli.error.analyze_collapsed cli.error.analyze_no_snapshots
                     cli.error.merge_names_parameter PROPERTIES FIXTURES_REQUIRED analyze_inputs)
# One realization: sigma is n/a, with the reason, never nan.
add_test(NAME cli.analyze_one_realization
         COMMAND ${_analyze} decay "${_cli_dir}/one_realization.h5" --t-lo 20 --t-hi 1000
                 -o "${_cli_dir}/one_realization_decay.h5")
set_tests_properties(cli.analyze_one_realization PROPERTIES LABELS cli FIXTURES_REQUIRED analyze_inputs
                     PASS_REGULAR_EXPRESSION "\\+- n/a \\(jackknife: one realization"
                     FAIL_REGULAR_EXPRESSION "nan")

# The pipeline's logs and commands show parameter-file numbers as written (0.9, not 0.90000000000000002).
add_test(NAME cli.pipeline_numbers_as_written COMMAND ${CMAKE_COMMAND} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/shortest_number_test.cmake)
set_tests_properties(cli.pipeline_numbers_as_written PROPERTIES LABELS cli)

# tools/shockgas-look: one command from a run to a PNG (fit and P(v,t)), no pipeline variables.
if(GNUPLOT_EXECUTABLE)
  add_test(NAME cli.setup.look_run
           COMMAND ${_sim} -N 2000 -r 0.5 -t 10000 -R 2 --histogram-times 1000,10000 -q -o "${_cli_dir}/look.h5")
  set_tests_properties(cli.setup.look_run PROPERTIES FIXTURES_SETUP look_run LABELS cli)
  add_test(NAME cli.look
           COMMAND ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR}
                   ${PROJECT_SOURCE_DIR}/tools/shockgas-look "${_cli_dir}/look.h5" -o "${_cli_dir}/look.png")
  set_tests_properties(cli.look PROPERTIES FIXTURES_REQUIRED look_run LABELS cli
                       PASS_REGULAR_EXPRESSION "decay exponent .*scaling exponent.*shockgas-look: .*look.png")
endif()
# Its version is that of the programs it runs.
add_test(NAME cli.look_version
         COMMAND ${CMAKE_COMMAND} -E env SHOCKGAS_BUILD=${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}/tools/shockgas-look --version)
set_tests_properties(cli.look_version PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "^shockgas-look [^ \n]+\n$")

if(SHOCKGAS_PYTHON)
  # The README's results rows, generated from a (miniature) pipeline tree.
  add_test(NAME cli.readme_tables
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/readme_tables_test.sh ${CMAKE_BINARY_DIR} ${SHOCKGAS_PYTHON}
                   "${_cli_dir}/readme_tables")
  set_tests_properties(cli.readme_tables PROPERTIES LABELS cli)
  add_test(NAME cli.setup.bad_init_files
           COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_bad_init.py "${_cli_dir}")
  set_tests_properties(cli.setup.bad_init_files PROPERTIES FIXTURES_SETUP bad_init LABELS cli)
  foreach(case_regex IN ITEMS "missing_velocity|missing dataset 'velocity'"
                              "length_mismatch|velocity has 5 values"
                              "unsorted|not sorted"
                              "out_of_range|outside \\[0, ring_length"
                              "nan_velocity|velocity\\[7\\] is not finite"
                              "no_ring_length|ring_length"
                              "too_fast|speeds up to 1e\\+305 carry particles 1e\\+308 far by t_max = 1000, beyond 2.25e\\+307 \\(2\\^1021\\)")
    string(FIND "${case_regex}" "|" _bar)
    string(SUBSTRING "${case_regex}" 0 ${_bar} _case)
    math(EXPR _start "${_bar} + 1")
    string(SUBSTRING "${case_regex}" ${_start} -1 _regex)
    shockgas_cli_error(init_${_case} "${_regex}" --init "${_cli_dir}/${_case}.h5")
    set_tests_properties(cli.error.init_${_case} PROPERTIES FIXTURES_REQUIRED bad_init)
  endforeach()
  add_test(NAME cli.init_file_run
           COMMAND ${_sim} --init "${_cli_dir}/good.h5" -t 20 -q -o "${_cli_dir}/good_run.h5")
  set_tests_properties(cli.init_file_run PROPERTIES FIXTURES_REQUIRED bad_init LABELS cli)
  # An init file is one start: an ensemble of it is refused with the way out.
  shockgas_cli_error(init_ensemble "one fixed initial condition.*--velocity-distribution"
                     --init "${_cli_dir}/good.h5" -R 4)
  set_tests_properties(cli.error.init_ensemble PROPERTIES FIXTURES_REQUIRED bad_init)
  # Both values named, as the --particles mismatch names both.
  shockgas_cli_error(init_ring_length_disagrees
                     "^shockgas-sim: error: --ring-length 7 disagrees with the ring length 8 of '[^']*good\\.h5'$"
                     --init "${_cli_dir}/good.h5" --ring-length 7)
  set_tests_properties(cli.error.init_ring_length_disagrees PROPERTIES FIXTURES_REQUIRED bad_init)
  # shockgas-burgers refuses an init file whose particles are not equally spaced, naming it.
  shockgas_burgers_error(off_lattice_init bad_init
    "^shockgas-burgers: error: init file '[^']*off_lattice\\.h5' starts from particles that are not equally spaced \\(particle 1 is off the lattice x_0 \\+ i L/N\\): the Burgers profile is built on the lattice"
    --init "${_cli_dir}/off_lattice.h5" -t 1)
endif()

# A good run prints the T(t) table and writes a complete file.
add_test(NAME cli.small_run
         COMMAND ${_sim} -N 1000 -r 0.9 -d 0.01 -t 100 -R 2 -o "${_cli_dir}/small.h5")
set_tests_properties(cli.small_run PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "complete \\(event engine")

# The pass-through engine by name: the same table and a complete file.
add_test(NAME cli.passthrough_run
         COMMAND ${_sim} -N 1000 -r 0.9 -d 0.01 -t 100 -R 2 --engine passthrough -o "${_cli_dir}/passthrough.h5")
set_tests_properties(cli.passthrough_run PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "complete \\(passthrough engine")

# A run stopped by a signal: its last progress line must not count the stopped
# realization as done (as "1/1 100.0% ETA 0 s"). Whether a line follows the stop
# depends on the interval (a loaded computer may print none).
# (It leaves a checkpoint, which would refuse its next run without --resume: removed first.)
add_test(NAME cli.progress_after_interrupt
         COMMAND bash -c "rm -f \"$1.checkpoint\" \"$1.checkpoint.previous\"; timeout -s INT 2 \"$0\" -N 100 -t 1e300 -R 1 -q -j 1 --progress-interval 1 -o \"$1\" 2>&1; true"
                 ${_sim} "${_cli_dir}/progress_interrupt.h5")
set_tests_properties(cli.progress_after_interrupt PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "shockgas-sim: interrupted"
                     FAIL_REGULAR_EXPRESSION "realizations 1/1")
# A batch log (stderr not a terminal, as under ctest) gets whole progress lines, at least the last.
add_test(NAME cli.progress_in_logs
         COMMAND ${_sim} -N 1000 -t 100 -R 2 -q --progress-interval 30 -o "${_cli_dir}/progress.h5")
set_tests_properties(cli.progress_in_logs PROPERTIES LABELS cli
                     PASS_REGULAR_EXPRESSION "shockgas-sim: progress: t = 100 +realizations 2/2 +100.0%")

# An ensemble from the other initial laws.
add_test(NAME cli.initial_law_run
         COMMAND ${_sim} -N 1000 --positions uniform --velocity-distribution gaussian -t 20 -R 3 -q
                 -o "${_cli_dir}/initial_law.h5")
set_tests_properties(cli.initial_law_run PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "complete \\(event engine")

# Ctrl-C: SIGINT mid-run writes what was computed, marked interrupted.
add_test(NAME cli.sigint_writes_interrupted
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/sigint_test.sh ${_sim} "${_cli_dir}/interrupted.h5")
set_tests_properties(cli.sigint_writes_interrupted PROPERTIES LABELS cli)

# --- parse and config-file problems, impossible engine choices ---
# Config files are written at configure time into the CLI work directory.
file(WRITE "${_cli_dir}/config_unknown_key.toml" "particles = 10\nrestitutoin = 0.5\n")
file(WRITE "${_cli_dir}/config_bad_value.toml" "particles = ten\n")
file(WRITE "${_cli_dir}/config_bad_restitution.toml" "particles = 10\nrestitution = 2.5\n")
file(WRITE "${_cli_dir}/config_good.toml" "particles = 100\nrestitution = 0.5\nthreshold = 0.01\nt-max = 10\n")
file(WRITE "${_cli_dir}/garbage.h5" "this is not an HDF5 file\n")
shockgas_cli_error(config_unknown_key "restitutoin" --config "${_cli_dir}/config_unknown_key.toml")
shockgas_cli_error(config_bad_value "particles|ten" --config "${_cli_dir}/config_bad_value.toml")
shockgas_cli_error(config_bad_restitution "restitution" --config "${_cli_dir}/config_bad_restitution.toml")
shockgas_cli_error(config_missing_file "no_such_config" --config "${_cli_dir}/no_such_config.toml")
shockgas_cli_error(engine_exact_inelastic "engine exact solves only the sticky gas" --engine exact -r 0.5 -N 10)
shockgas_cli_error(engine_unknown "engine must be" --engine warp -N 10)
shockgas_cli_error(engine_passthrough_sticky "engine passthrough cannot run this: sticky sub-threshold"
                   --engine passthrough -r 0.5 -d 0.01 --subthreshold sticky -N 10)
shockgas_cli_error(particles_not_a_number "particles|abc" -N abc)
# Counts in scientific notation are the whole numbers they write (-N 1e5); a fraction is refused by name.
shockgas_cli_error(particles_fraction "^shockgas-sim: error: --particles: must be a whole number, not '1.5e0'$" -N 1.5e0)
shockgas_cli_error(realizations_fraction "^shockgas-sim: error: --realizations: must be a whole number, not '2.25e1'$"
                   -N 10 -R 2.25e1)
add_test(NAME cli.counts_in_scientific_notation
         COMMAND ${CMAKE_COMMAND} -DSIM=$<TARGET_FILE:shockgas-sim> -DDUMP=$<TARGET_FILE:shockgas-dump>
                 -DWORK=${_cli_dir}/scientific -P ${CMAKE_CURRENT_LIST_DIR}/scientific_counts_test.cmake)
set_tests_properties(cli.counts_in_scientific_notation PROPERTIES LABELS cli)
shockgas_cli_error(particles_too_many "below 2\\^31" -N 3000000000)
shockgas_cli_error(unknown_option "frobnicate" -N 10 --frobnicate 3)
shockgas_cli_error(restitution_nan "restitution" -N 10 -r nan)
shockgas_cli_error(t_max_inf "t_max" -N 10 -t inf)
shockgas_cli_error(threads_negative "threads" -N 10 -j -1)
shockgas_cli_error(samples_per_decade_zero "samples per decade" -N 10 --samples-per-decade 0)
shockgas_cli_error(histogram_bins_huge "histogram bins must lie in" -N 10 --histogram-times 1 --histogram-bins 1000000000)
shockgas_cli_error(ring_length_negative "ring length" -N 10 --ring-length -1)
shockgas_cli_error(realizations_zero "realizations" -N 10 -R 0)
shockgas_cli_error(histogram_bins_zero "histogram bins" -N 10 --histogram-bins 0)
shockgas_cli_error(snapshot_interval_zero "snapshot interval" -N 10 --snapshot-interval 0)
shockgas_cli_error(collapse_speed_negative "collapse speed" -N 10 --collapse-speed -1)
# Above delta > 0 the collapse criterion would declare a collapse the threshold forbids.
shockgas_cli_error(collapse_speed_above_threshold
                   "collapse speed 0\\.1 exceeds the threshold delta = 0\\.01: every inelastic collision is then at least delta"
                   -N 100 -r 0.5 -d 0.01 --collapse-speed 0.1)
# A snapshot interval past t_max would take no snapshot: refused, not run without a word.
shockgas_cli_error(snapshot_interval_past_t_max "snapshot interval 20 exceeds t_max = 10: no snapshot would be taken"
                   -N 10 -t 10 --snapshot-interval 20)
shockgas_cli_error(seed_negative "seed|-5" -N 10 --seed -5)
shockgas_cli_error(init_garbage "not a readable HDF5 file" --init "${_cli_dir}/garbage.h5")
shockgas_cli_error(init_directory "init" --init "${_cli_dir}")
add_test(NAME cli.config_file_run
         COMMAND ${_sim} --config "${_cli_dir}/config_good.toml" -q -o "${_cli_dir}/config_run.h5")
set_tests_properties(cli.config_file_run PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "complete \\(event engine")

# --- runs that survive being killed ---
# SIGKILL mid-run, then --resume: bit-identical to an uninterrupted run.
if(SHOCKGAS_PYTHON)
  add_test(NAME cli.sigkill_resume_bit_identical
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/sigkill_resume_test.sh ${_sim} ${SHOCKGAS_PYTHON}
                   ${CMAKE_CURRENT_SOURCE_DIR}/compare_outputs.py "${_cli_dir}/sigkill")
  set_tests_properties(cli.sigkill_resume_bit_identical PROPERTIES LABELS cli TIMEOUT 300)
endif()
# --- faults that must not lose work or change results ---
if(SHOCKGAS_PYTHON)
  add_test(NAME cli.faults.damaged_checkpoint
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/damaged_checkpoint_test.sh ${_sim} ${SHOCKGAS_PYTHON}
                   ${CMAKE_CURRENT_SOURCE_DIR}/compare_outputs.py "${_cli_dir}/damaged_checkpoint")
  set_tests_properties(cli.faults.damaged_checkpoint PROPERTIES LABELS cli TIMEOUT 300)
  # Where a paper build in progress stands (tools/fidelity_report.py --progress): a running part's spent CPU
  # taken off its remaining estimate, a checkpoint of another version set aside, fig_tail's sampler.
  add_test(NAME cli.progress_report
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/progress_report_test.sh ${_sim} $<TARGET_FILE:shockgas-spheres>
                   ${SHOCKGAS_PYTHON}
                   ${PROJECT_SOURCE_DIR}/tools/fidelity_report.py "${_cli_dir}/progress_report")
  set_tests_properties(cli.progress_report PROPERTIES LABELS cli TIMEOUT 120 ENVIRONMENT "${SHOCKGAS_TEST_PYTHONPATH}")
  # A provisional Fig. 4 from the finished parts of a paper build (tools/provisional-fig4); with r = 0.5
  # left out, r = 0.9's points under r = 0.9's label (the legend read back from an SVG of the same plot).
  add_test(NAME cli.provisional_fig4
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/provisional_fig4_test.sh ${_sim} $<TARGET_FILE:shockgas-merge>
                   $<TARGET_FILE:shockgas-dump> $<TARGET_FILE:shockgas-analyze> ${SHOCKGAS_PYTHON}
                   "${_cli_dir}/provisional_fig4")
  set_tests_properties(cli.provisional_fig4 PROPERTIES LABELS cli TIMEOUT 300)
  # A build in the background: start, stop with a last checkpoint, resume (tools/paper-tier); hints that
  # name --build DIR, a second start with another target refused (exit 2).
  add_test(NAME cli.paper_tier
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/paper_tier_test.sh ${PROJECT_SOURCE_DIR}/tools/paper-tier ${_sim}
                   "${_cli_dir}/paper_tier")
  # The tool builds at the lowest CPU priority (nice 19, and its own session's autogroup), so this test's
  # builds yield to everything else on the computer: a minute or two alone or beside the other ci tests,
  # several minutes under CI's full load on 2 cores; the timeout leaves room for a slower computer and
  # only bounds a hang.
  set_tests_properties(cli.paper_tier PROPERTIES LABELS cli TIMEOUT 900)
endif()
foreach(_case IN ITEMS file_size_output file_size_checkpoint stale_temporaries lock resume_other_parameters
                      rerun_without_resume memory_fewer_at_once hangup resume_other_build resume_same_simulator
                      resume_complete_output)
  add_test(NAME cli.faults.${_case}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/faults_test.sh ${_case} ${_sim} "${_cli_dir}/faults"
                   "${SHOCKGAS_PYTHON}" ${CMAKE_CURRENT_SOURCE_DIR}/compare_outputs.py)
  # 300 s as the other fault tests: hangup and resume_other_build make three N = 20 000 runs, which
  # take the sanitizer build one to two minutes each on 2 cores beside other tests; a hang still ends
  # in a timeout.
  set_tests_properties(cli.faults.${_case} PROPERTIES LABELS cli TIMEOUT 300 ENVIRONMENT "${SHOCKGAS_TEST_PYTHONPATH}")
endforeach()
if(NOT SHOCKGAS_PYTHON)  # these compare outputs (and resume_other_build and resume_complete_output edit files) with Python
  set_tests_properties(cli.faults.file_size_checkpoint cli.faults.hangup cli.faults.resume_other_build
                       cli.faults.resume_other_parameters
                       cli.faults.resume_same_simulator cli.faults.resume_complete_output PROPERTIES DISABLED TRUE)
endif()
# A budget below one realization (100000 particles: about 41 MiB with checkpoints) is refused,
# naming the part of it that no N lowers.
shockgas_cli_error(faults_memory_refused
                   "not enough memory: one realization of N = 100000 needs about [0-9]+ MiB \\(16 MiB of it the program itself, whatever N\\), but 30 MiB may be used \\(--max-memory\\); lower N"
                   -N 100000 -R 2 -j 2 -t 10 --max-memory 30M)
# A budget below the program itself: no N fits, so lowering N is not the advice.
shockgas_cli_error(memory_below_the_program
                   "^shockgas-sim: error: not enough memory: any run needs more than 16 MiB \\(the program itself, whatever N\\), but 1 KiB may be used \\(--max-memory\\); raise --max-memory$"
                   -N 10 -t 10 --max-memory 1K)
# Many realizations of a small N: what does not fit is their records, which lowering N would not
# shrink, so the advice is parts, not "lower N".
shockgas_cli_error(memory_many_realizations
                   "^shockgas-sim: error: not enough memory: 100000000 realizations need about [0-9.]+ GiB, [0-9.]+ GiB of it for their records .* but 8.0 GiB may be used \\(--max-memory\\); give each run at most [0-9]+ realizations: split the ensemble into parts with -R and --first-realization and join them with shockgas-merge, or set --max-memory$"
                   -N 1000 -R 100000000 -t 10 --max-memory 8G)
shockgas_cli_error(max_memory_not_a_size "--max-memory '3X' is not a size" -N 100 --max-memory 3X)
shockgas_cli_error(checkpoint_interval_negative "checkpoint-interval" -N 10 --checkpoint-interval -1)
shockgas_cli_error(checkpoint_unwritable "directory .* does not exist" -N 10 --checkpoint "${_cli_dir}/absent_dir/c.h5")

# ---------------------------------------------------------------------------
# Outputs never destroy inputs or other files; bad and damaged inputs are
# refused with one line. Kept in one
# block at the end of this file.
# ---------------------------------------------------------------------------
set(_merge $<TARGET_FILE:shockgas-merge>)
set(_dump $<TARGET_FILE:shockgas-dump>)
# Seeds: CLI11 read 2^64 and 10^23 as 2^64 - 1 (three seeds, one run), and
# seeds from 2^63 on were stored (signed) as negative numbers.
shockgas_cli_error(seed_two_to_64 "--seed: must be an integer from 0 to 2\\^63 - 1 = 9223372036854775807, not '18446744073709551616'"
                   -N 10 --seed 18446744073709551616)
shockgas_cli_error(seed_huge "--seed: must be an integer from 0 to 2\\^63 - 1" -N 10 --seed 99999999999999999999999)
shockgas_cli_error(seed_two_to_63 "--seed: must be an integer from 0 to 2\\^63 - 1" -N 10 --seed 9223372036854775808)
shockgas_cli_error(seed_not_a_number "--seed: must be an integer" -N 10 --seed 12abc)
# Intervals: nan passed CLI11's NonNegativeNumber.
shockgas_cli_error(progress_interval_nan "--progress-interval: must be a finite number >= 0, not 'nan'"
                   -N 10 --progress-interval nan)
shockgas_cli_error(progress_interval_inf "--progress-interval: must be a finite number >= 0" -N 10 --progress-interval inf)
shockgas_cli_error(checkpoint_interval_nan "--checkpoint-interval: must be a finite number >= 0"
                   -N 10 --checkpoint-interval nan)
# A config file's [section] header is refused in words, not as "unknown option 'section.++'".
file(WRITE "${_cli_dir}/config_section.toml" "[run]\nparticles = 10\n")
file(WRITE "${_cli_dir}/config_dotted_key.toml" "particles = 10\nrun.t-max = 10\n")
shockgas_cli_error(config_section
                   "^shockgas-sim: error: section '\\[run\\]' in .*config_section.toml: sections are not supported \\(write every option at the top level\\)$"
                   --config "${_cli_dir}/config_section.toml")
shockgas_cli_error(config_dotted_key "unknown option 'run.t-max' in .*config_dotted_key.toml: sections and dotted keys are not supported"
                   --config "${_cli_dir}/config_dotted_key.toml")
# --checkpoint naming the output: the run ended "complete" and left no output.
shockgas_cli_error(checkpoint_is_output "checkpoint '.*checkpoint_is_output.h5' is the output '.*checkpoint_is_output.h5'"
                   -N 10 -t 1 --checkpoint "${_cli_dir}/checkpoint_is_output.h5")
# shockgas-dump: a realization or snapshots the file does not have are refused
# (not a header alone with exit 0), and the refusal leaves no output, not an empty one.
add_test(NAME cli.setup.dump_input
         COMMAND ${_sim} -N 200 -t 10 -R 2 --sample-times 2 --snapshot-times 1,5 -q -o "${_cli_dir}/dump_input.h5")
set_tests_properties(cli.setup.dump_input PROPERTIES FIXTURES_SETUP dump_input LABELS cli)
shockgas_tool_error(dump_realization_beyond "^shockgas-dump: error: --realization 5: '.*dump_input.h5' has 2 realizations \\(0 to 1\\)$"
                    ${_dump} snapshots "${_cli_dir}/dump_input.h5" --realization 5
                    -o "${_cli_dir}/dump_realization_beyond.out.h5")
shockgas_tool_error(dump_realization_negative "--realization must be >= 0"
                    ${_dump} snapshots "${_cli_dir}/dump_input.h5" --realization -1
                    -o "${_cli_dir}/dump_realization_negative.out.h5")
shockgas_tool_error(dump_no_snapshots "^shockgas-dump: error: '.*one_realization.h5' has no snapshots"
                    ${_dump} snapshots "${_cli_dir}/one_realization.h5" -o "${_cli_dir}/dump_no_snapshots.out.h5")
# -o /dev/full: the full disk is an error (it exited 0). /dev/full itself is
# not passed to expect_error.sh as the output, which it would remove.
shockgas_tool_error(dump_full_disk "^shockgas-dump: error: cannot write '/dev/full': No space left on device$"
                    ${_dump} snapshots "${_cli_dir}/dump_input.h5" -o /dev/full)
set_tests_properties(cli.error.dump_realization_beyond cli.error.dump_realization_negative cli.error.dump_full_disk
                     PROPERTIES FIXTURES_REQUIRED dump_input)
set_tests_properties(cli.error.dump_no_snapshots PROPERTIES FIXTURES_REQUIRED analyze_inputs)
# Refusals that must also leave the file at stake unchanged, and dump's outputs.
foreach(_case IN ITEMS checkpoint_not_a_checkpoint checkpoint_is_init output_is_init checkpoint_removed
                      merge_output_is_part merge_checkpoint dump_output_is_input dump_outputs output_not_creatable
                      output_not_an_output)
  add_test(NAME cli.io_safety.${_case}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/io_safety_test.sh ${_case} "${_cli_dir}/io_safety" ${_sim} ${_merge}
                   ${_dump} "${SHOCKGAS_PYTHON}")
  set_tests_properties(cli.io_safety.${_case} PROPERTIES LABELS cli TIMEOUT 120)
endforeach()
# Damaged or inconsistent files (h5py edits of a good run): one line naming the
# file and the dataset or attribute, never numbers read beyond a dataset's end.
if(SHOCKGAS_PYTHON)
  add_test(NAME cli.setup.inconsistent_runs
           COMMAND ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_inconsistent_runs.py
                   "${_cli_dir}/dump_input.h5" "${_cli_dir}")
  set_tests_properties(cli.setup.inconsistent_runs PROPERTIES FIXTURES_SETUP inconsistent_runs
                       FIXTURES_REQUIRED dump_input LABELS cli)
  shockgas_tool_error(dump_short_velocity
                      "^shockgas-dump: error: '.*short_velocity.h5' is inconsistent: dataset /snapshots/0/velocity has [0-9]+ values, expected [0-9]+"
                      ${_dump} snapshots "${_cli_dir}/short_velocity.h5" -o "${_cli_dir}/dump_short_velocity.out.h5")
  shockgas_tool_error(merge_short_collisions
                      "^shockgas-merge: error: '.*short_collisions.h5' is inconsistent: dataset /timeseries/collisions_per_particle has"
                      ${_merge} "${_cli_dir}/short_collisions.h5" -o "${_cli_dir}/merge_short_collisions.out.h5")
  shockgas_tool_error(merge_bad_sample_times
                      "^shockgas-merge: error: '.*bad_sample_times.h5': root attribute sample_times = '2,abc' is not a comma-separated list of times"
                      ${_merge} "${_cli_dir}/bad_sample_times.h5" -o "${_cli_dir}/merge_bad_sample_times.out.h5")
  shockgas_tool_error(merge_unknown_status
                      "^shockgas-merge: error: '.*unknown_status.h5': root attribute status = 'checkpoint' is none of complete, collapsed, interrupted$"
                      ${_merge} "${_cli_dir}/unknown_status.h5" -o "${_cli_dir}/merge_unknown_status.out.h5")
  set_tests_properties(cli.error.dump_short_velocity cli.error.merge_short_collisions cli.error.merge_bad_sample_times
                       cli.error.merge_unknown_status PROPERTIES FIXTURES_REQUIRED inconsistent_runs)
endif()

# shockgas-spheres refuses what it cannot run in one line, status 2, and writes no output
# (docs/spheres.md, "The model").
foreach(_case IN ITEMS "dimension;^shockgas-spheres: error: --dimension 4 is not 2 or 3$;-D;4"
                      "box_too_small;less than 3 diameters: use more particles$;-N;4"
                      "restitution_zero;disks and spheres do not merge;-r;0"
                      "threshold_negative;--threshold -1 must be finite and >= 0$;-d;-1"
                      "insertion_too_dense;--start lattice goes further;--phi;0.4"
                      "lattice_too_dense;is outside .0, 0.5236.,;--start;lattice;--phi;0.6"
                      "start_method;unknown start method 'random' .insertion or lattice.$;--start;random")
  shockgas_error_case(spheres "${_case}" $<TARGET_FILE:shockgas-spheres> -t 1)
endforeach()
