# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -DSIM=shockgas-sim -DDUMP=shockgas-dump -DWORK=dir -P scientific_counts_test.cmake
# Counts written in scientific notation (-N 1.2e3) run as the whole numbers they are: the run's
# file records N = 1200, R = 2 and 80 histogram bins.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${SIM}" -N 1.2e3 -R 2e0 --histogram-bins 8E+1 --histogram-times 1 -t 1 -q
                        -o "${WORK}/run.h5"
                RESULT_VARIABLE status ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "shockgas-sim -N 1.2e3 -R 2e0 --histogram-bins 8E+1 failed (${status}): ${errors}")
endif()
execute_process(COMMAND "${DUMP}" gnuplot-vars "${WORK}/run.h5" / --prefix run OUTPUT_VARIABLE vars
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "shockgas-dump failed (${status})")
endif()
foreach(expected IN ITEMS "run_particles = 1200" "run_realizations = 2" "run_histogram_bins = 80")
  string(FIND "${vars}" "${expected}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the run does not record '${expected}':\n${vars}")
  endif()
endforeach()
message(STATUS "ok: -N 1.2e3 -R 2e0 --histogram-bins 8E+1 ran as N = 1200, R = 2, 80 bins")
