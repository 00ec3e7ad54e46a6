# SPDX-License-Identifier: GPL-3.0-or-later
# Run at build time (cmake -P). Writes STAMP = SHA-256 over the simulator's
# sources and the compiler and flags (shockgas_source_hash, SourceHash.cmake),
# rewriting the file only when that hash changes. Simulations depend on this
# stamp instead of on the shockgas-sim binary: the binary is relinked at every
# commit (it embeds git describe for provenance), but a simulation is stale only
# when the code that computes it, or the way it is compiled, changed. The same
# hash is compiled into the programs (BuildInfo.cmake) and recorded in every
# output and checkpoint as simulator_sha256.
#
# DIRECTORIES is separated by "|", not ";": a ";" inside a -D value reaches
# this script escaped ("\;"), which makes the whole value one directory that
# does not exist, and the stamp would hash no file at all (so changing the
# simulator would never rerun a simulation). STAMP.files lists
# what was hashed; ctest pipeline.stamp_covers_sim_sources checks it.
include(${CMAKE_CURRENT_LIST_DIR}/SourceHash.cmake)
string(REPLACE "|" ";" _directories "${DIRECTORIES}")
shockgas_source_hash(_stamp _content "${SOURCE_DIR}" "${_directories}" "${COMPILER_INFO}")
set(_old "")
if(EXISTS "${STAMP}")
  file(READ "${STAMP}" _old)
endif()
if(NOT _old STREQUAL "${_stamp}")
  file(WRITE "${STAMP}" "${_stamp}")
endif()
if(NOT _old STREQUAL "${_stamp}" OR NOT EXISTS "${STAMP}.files")
  file(WRITE "${STAMP}.files" "${_content}")
endif()
