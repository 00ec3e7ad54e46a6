# SPDX-License-Identifier: GPL-3.0-or-later
# Archival reproduction (docs/archive.md).
#   archive          every figure at this fidelity -> shockgas-<describe>-<fidelity>.tar.gz
#   archive_fig3     Fig. 3 alone (< 1 s of simulation) -> ...-<fidelity>-fig3.tar.gz; used by the tests
#   reproduce-check  checks the newest archive in this build directory, or -DSHOCKGAS_ARCHIVE=<file>
include(${PROJECT_SOURCE_DIR}/cmake/Archive.cmake)
get_property(_archive_figures GLOBAL PROPERTY SHOCKGAS_FIGURES)
shockgas_add_archive(archive FIGURES ${_archive_figures} DEPENDS figures)
shockgas_add_archive(archive_fig3 FIGURES fig3 SUFFIX -fig3 DEPENDS fig3)

set(SHOCKGAS_ARCHIVE "" CACHE FILEPATH "Archive checked by the reproduce-check target (default: the newest in the build directory)")
if(SHOCKGAS_ARCHIVE)
  set(_archive_to_check "${SHOCKGAS_ARCHIVE}")
else()
  set(_archive_to_check "${CMAKE_BINARY_DIR}")
endif()
add_custom_target(reproduce-check
  COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/tools/reproduce-check ${_archive_to_check}
          --work-dir ${CMAKE_BINARY_DIR}/reproduce-check
  USES_TERMINAL
  COMMENT "Rebuilding an archive's figures from its own source in a fresh directory and comparing"
  VERBATIM)
