# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -P: the pipeline's numbers as they were written (cmake/ShortestNumber.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/ShortestNumber.cmake)
foreach(case "0.9|0.9" "0.99|0.99" "0.0125|0.0125" "0.3|0.3" "2.5e-3|0.0025" "-0.5|-0.5" "100000|100000"
             # 17 significant digits stay: no shorter decimal is the same double.
             "0.12345678901234567|0.12345678901234566"
             "0.00012345678901234567|0.00012345678901234567")
  string(REPLACE "|" ";" pair "${case}")
  list(GET pair 0 literal)
  list(GET pair 1 expected)
  string(JSON read GET "[${literal}]" 0)  # what the pipeline reads from a parameter file
  _shockgas_shortest_number("${read}" shortest)
  if(NOT shortest STREQUAL expected)
    message(FATAL_ERROR "${literal}: read as ${read}, shortened to ${shortest}, expected ${expected}")
  endif()
endforeach()
message(STATUS "ok")
