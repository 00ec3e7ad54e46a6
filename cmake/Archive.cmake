# SPDX-License-Identifier: GPL-3.0-or-later
# Archival reproduction (docs/archive.md). tools/reproduce-check does the work;
# these functions only pass it what CMake knows about the build.
#
# shockgas_add_archive(<target> FIGURES <fig...> [SUFFIX <s>] [DEPENDS <targets...>])
#   <target> writes <build>/shockgas-<git describe>-<fidelity><s>.tar.gz from the
#   figures' parameter files, runs, results, data and plots, after building DEPENDS.
#   git describe is taken when the target runs, not at configure time.
set(SHOCKGAS_ARCHIVE_MAX_RAW_MB 50 CACHE STRING
    "Raw HDF5 runs larger than this (MB) are listed in an archive's MANIFEST by SHA-256 and parameters, not copied")

function(shockgas_add_archive target)
  cmake_parse_arguments(ARG "" "SUFFIX" "FIGURES;DEPENDS" ${ARGN})
  string(REPLACE ";" "," figures "${ARG_FIGURES}")
  add_custom_target(${target}
    COMMAND ${SHOCKGAS_PYTHON} ${PROJECT_SOURCE_DIR}/tools/reproduce-check pack
            --build-dir ${CMAKE_BINARY_DIR} --source-dir ${PROJECT_SOURCE_DIR}
            --fidelity ${SHOCKGAS_FIDELITY} --figures ${figures} --suffix=${ARG_SUFFIX}
            --max-raw-mb ${SHOCKGAS_ARCHIVE_MAX_RAW_MB}
            --toolchain "compiler=${SHOCKGAS_COMPILER}"
                        "compiler_flags=${SHOCKGAS_COMPILER_FLAGS}" "build_type=${CMAKE_BUILD_TYPE}"
                        "cxx_compiler=${CMAKE_CXX_COMPILER}" "hdf5_version=${HDF5_VERSION}"
                        "gsl_version=${GSL_VERSION}" "gnuplot=${GNUPLOT_EXECUTABLE}"
                        "cmake_version=${CMAKE_VERSION}" "python=${SHOCKGAS_PYTHON}"
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
    COMMENT "Archiving ${ARG_FIGURES} (${SHOCKGAS_FIDELITY}) with MANIFEST and source"
    VERBATIM)
  if(ARG_DEPENDS)
    add_dependencies(${target} ${ARG_DEPENDS})
  endif()
endfunction()
