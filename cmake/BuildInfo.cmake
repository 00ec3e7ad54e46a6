# SPDX-License-Identifier: GPL-3.0-or-later
# Run at build time (cmake -P): captures `git describe --always --dirty` so the
# version recorded in every output file is the code that was actually built,
# and simulator_sha256, the hash of the simulator's sources, compiler and flags
# (shockgas_source_hash over SIM_DIRECTORIES, "|"-separated as in
# SourceStamp.cmake): two builds with the same hash compute the same numbers, so
# a checkpoint of one can be continued by the other, bit for bit, whatever else
# changed in the checkout (docs, analysis, tests).
# configure_file only rewrites the output when its content changes, so an
# unchanged checkout does not trigger recompilation.
include(${CMAKE_CURRENT_LIST_DIR}/SourceHash.cmake)
execute_process(
  COMMAND git describe --always --dirty --tags
  WORKING_DIRECTORY "${SOURCE_DIR}"
  OUTPUT_VARIABLE SHOCKGAS_GIT_DESCRIBE
  OUTPUT_STRIP_TRAILING_WHITESPACE
  ERROR_QUIET
  RESULT_VARIABLE git_result)
if(NOT git_result EQUAL 0 OR SHOCKGAS_GIT_DESCRIBE STREQUAL "")
  set(SHOCKGAS_GIT_DESCRIBE "unknown (not a git checkout)")
endif()
string(REPLACE "|" ";" _directories "${SIM_DIRECTORIES}")
shockgas_source_hash(SHOCKGAS_SIMULATOR_SHA256 _listing "${SOURCE_DIR}" "${_directories}" "${COMPILER_INFO}")
configure_file("${INPUT}" "${OUTPUT}" @ONLY)
