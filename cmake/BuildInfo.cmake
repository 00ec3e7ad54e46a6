# Run at build time (cmake -P): captures `git describe --always --dirty` so the
# version recorded in every output file is the code that was actually built.
# configure_file only rewrites the output when its content changes, so an
# unchanged checkout does not trigger recompilation.
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
configure_file("${INPUT}" "${OUTPUT}" @ONLY)
