# SPDX-License-Identifier: GPL-3.0-or-later
# Run at build time by each simulation rule (paper_targets/pipeline.cmake):
#   cmake -DOUTPUT=<run.h5> -DSTAGED=<run.running.h5> "-DINPUTS=<file>|<file>..." -P RunSimulation.cmake
#         -- <program> <arguments...>
# runs the program, which writes STAGED, renames STAGED to OUTPUT once the program has exited 0, and
# then records in OUTPUT.made the SHA-256 of each of INPUTS (the run's .args file and the simulator's
# stamp: what decides its numbers).
#
# Make reruns a rule when an input is newer than its output. The stamp is rewritten whenever its hash
# changes, so a round trip through a commit of other simulator sources (checking an old commit out and
# coming back) makes it newer than every finished run, whose numbers it would decide exactly as before.
# So before running, a rule whose OUTPUT exists and whose OUTPUT.made records the inputs' present
# content keeps OUTPUT (touched, so make takes it as made) instead of running the simulation again.
# A run made without a record (by `paper-tier commands` elsewhere, or before records were kept) is
# simulated again when its inputs are touched, as before.
if(NOT DEFINED OUTPUT OR NOT DEFINED STAGED OR NOT DEFINED INPUTS)
  message(FATAL_ERROR "RunSimulation.cmake needs -DOUTPUT, -DSTAGED and -DINPUTS")
endif()
set(command)
set(after_separator FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
  if(after_separator)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(after_separator TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "RunSimulation.cmake: no program after --")
endif()

string(REPLACE "|" ";" inputs "${INPUTS}")
set(record "")
foreach(input IN LISTS inputs)
  file(SHA256 "${input}" hash)
  string(APPEND record "${hash}  ${input}\n")
endforeach()

set(made "${OUTPUT}.made")
if(EXISTS "${OUTPUT}" AND EXISTS "${made}")
  file(READ "${made}" recorded)
  if(recorded STREQUAL record)
    file(TOUCH_NOCREATE "${OUTPUT}")
    message(STATUS "${OUTPUT} was made from the same parameters and simulator sources: kept")
    return()
  endif()
endif()

file(REMOVE "${made}")
execute_process(COMMAND ${command} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  # The program has said why (an interrupted run exits 130 after its last checkpoint).
  message(FATAL_ERROR "${OUTPUT}: the simulation ended with status ${status}")
endif()
file(RENAME "${STAGED}" "${OUTPUT}")
file(WRITE "${made}" "${record}")
