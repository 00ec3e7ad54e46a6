# SPDX-License-Identifier: GPL-3.0-or-later
# The validity map's programs end to end, on the hand-made map of the unit tests
# (tests/validity_map_fixture.hpp, written by make_validity_map): shockgas-plan's
# answer, its refusals (one line, status 2) and --help, and shockgas-sim's warning.
set(_validity_dir "${CMAKE_CURRENT_BINARY_DIR}/work/cli/validity")
file(MAKE_DIRECTORY "${_validity_dir}")
set(_validity_map "${_validity_dir}/map.h5")
set(_plan $<TARGET_FILE:shockgas-plan>)

add_executable(make_validity_map cli/make_validity_map.cpp)
target_link_libraries(make_validity_map PRIVATE shockgas::analysis shockgas_warnings)
add_test(NAME cli.setup.validity_map COMMAND make_validity_map "${_validity_map}")
set_tests_properties(cli.setup.validity_map PROPERTIES FIXTURES_SETUP validity_map LABELS cli)

# By 3 sigma, T stays as in the sticky gas to t = 30 for every delta at r = 0.9; delta = 0.1 elastic makes
# the fewest collisions (sqrt(30) per particle).
add_test(NAME cli.plan_answer
         COMMAND ${_plan} --map "${_validity_map}" -t 30 -N 100000 -r 0.9 --observable temperature --tolerance 3sigma)
set_tests_properties(cli.plan_answer PROPERTIES FIXTURES_REQUIRED validity_map LABELS cli
  PASS_REGULAR_EXPRESSION "^cheapest: delta = 0\\.1, sub-threshold elastic: temperature stays within 3sigma .*\ncost at N = 100000: 5\\.48 collisions per particle by t = 30.*\nmap: test map, shockgas fixture")
# An r the map lacks: one line listing the measured ones, status 2 (expect_error.sh; no file is written,
# so its OUTPUT argument names none).
add_test(NAME cli.error.plan_r_outside
         COMMAND ${_expect}
                 "^shockgas-plan: error: r = 0\\.7 is not among the map's restitutions: it measured r = 0\\.5, 0\\.9"
                 "${_validity_dir}/plan_r_outside.none" --
                 ${_plan} --map "${_validity_map}" -t 30 -N 100000 -r 0.7 --observable temperature --tolerance 3sigma)
set_tests_properties(cli.error.plan_r_outside PROPERTIES FIXTURES_REQUIRED validity_map LABELS cli)
# No map: how to make one.
add_test(NAME cli.error.plan_no_map
         COMMAND ${_expect} "^shockgas-plan: error: no validity map: .*--target fig_validity.*--map FILE$"
                 "${_validity_dir}/plan_no_map.none" --
                 ${_plan} --map "" -t 30 -N 100000 -r 0.9 --observable temperature --tolerance 3sigma)
set_tests_properties(cli.error.plan_no_map PROPERTIES LABELS cli)
# --help documents every option, with its units.
foreach(_case IN ITEMS "t_max|--t-max.*units of initial spacing / initial velocity scale"
                      "particles|--particles.*a count" "restitution|--restitution.*dimensionless"
                      "observable|--observable.*temperature, kurtosis" "tolerance|--tolerance.*3sigma.*1percent.*5percent"
                      "map|--map.*/validity_map")
  string(REPLACE "|" ";" _case "${_case}")
  list(GET _case 0 _name)
  list(GET _case 1 _words)
  add_test(NAME cli.plan_help_${_name} COMMAND ${_plan} --help)
  set_tests_properties(cli.plan_help_${_name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "${_words}")
endforeach()

# shockgas-sim warns past the map's t* and only there, and computes the same run either way. It sets
# SHOCKGAS_VALIDITY_MAP itself for its last case, over the suite's empty one (tests/CMakeLists.txt).
if(SHOCKGAS_PYTHON)
  add_test(NAME cli.sim_validity_warning
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/validity_warning_test.sh ${_sim} "${_validity_map}"
                   "${_validity_dir}/warning" ${SHOCKGAS_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/compare_outputs.py)
  set_tests_properties(cli.sim_validity_warning PROPERTIES FIXTURES_REQUIRED validity_map LABELS cli TIMEOUT 120)
endif()
# A map named by the user that is not there is refused, as any missing input.
shockgas_cli_error(validity_map_missing "^shockgas-sim: error: cannot read the validity map: file '.*no_such_map.h5' does not exist$"
                   -N 100 -t 10 --validity-map "${_validity_dir}/no_such_map.h5")
