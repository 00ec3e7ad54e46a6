# SPDX-License-Identifier: GPL-3.0-or-later
# Install rules (docs/install.md), in the usual GNUInstallDirs layout:
#
#   bin/                                 shockgas-sim, -merge, -dump, -burgers, -analyze, -tail, -plan
#   include/shockgas/<room>/             the public headers of each library (model, io, engines,
#                                        run, tail, ranks, spheres, analysis)
#   lib/<multiarch>/                     libshockgas_<room>.a
#   lib/<multiarch>/cmake/shockgas/      find_package(shockgas CONFIG): shockgas::sim (all of the
#                                        simulator), each room's library, shockgas::analysis
#   lib/python3*/...-packages/shockgas/  the Python reader (cmake/InstallPythonModule.cmake picks the folder)
#   share/shockgas/                      a CMake project that remakes the figures from the installed
#                                        programs: paper_targets/ (parameter files and pipeline),
#                                        figures/ (gnuplot scripts and style), python/ (exact theory),
#                                        tools/ (fidelity report, reproduce-check)
#   share/man/man1/                      man pages made from --help (cmake/ManPages.cmake)
#   share/doc/shockgas/                  README.md, ARCHITECTURE.md, CHANGELOG.md, docs/, analysis/README.md,
#                                        LICENSE and the Debian copyright file (also in share/doc/shockgas-dev/)
#
# Two components, which become the two Debian packages (cmake/Packaging.cmake):
# "runtime" (programs, Python, data, man pages, docs) and "dev" (headers,
# libraries, CMake package).

include(CMakePackageConfigHelpers)

set(SHOCKGAS_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/shockgas"
    CACHE STRING "Where find_package(shockgas) finds shockgasConfig.cmake, relative to the prefix")
set(SHOCKGAS_INSTALL_DATADIR "${CMAKE_INSTALL_DATADIR}/shockgas")
mark_as_advanced(SHOCKGAS_INSTALL_CMAKEDIR)

# The libraries, one a room (the umbrella shockgas_sim is an interface target, no file of its own).
set(SHOCKGAS_LIBRARIES shockgas_model shockgas_io shockgas_engines shockgas_run shockgas_tail shockgas_ranks
                       shockgas_spheres shockgas_analysis)
set(SHOCKGAS_PROGRAMS shockgas-sim shockgas-merge shockgas-dump shockgas-burgers shockgas-analyze shockgas-tail
                      shockgas-plan shockgas-spheres)

# First of all the rules: the built files are all there, or nothing is installed
# (cmake/InstallCheck.cmake; install-needs.txt is written at the end of this file).
install(CODE "set(SHOCKGAS_BUILD_DIR \"${PROJECT_BINARY_DIR}\")
  include(\"${PROJECT_SOURCE_DIR}/cmake/InstallCheck.cmake\")"
  ALL_COMPONENTS)

# Libraries, programs and headers. The programs are exported too, apart
# (shockgasPrograms.cmake, in the runtime component, needing nothing found): the
# installed figure project runs them by target name as the source build does,
# without the -dev package or a compiler.
install(TARGETS shockgas_sim ${SHOCKGAS_LIBRARIES}
        EXPORT shockgasTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS ${SHOCKGAS_PROGRAMS}
        EXPORT shockgasPrograms
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
# Whole folders, so that a header added to a library is installed without
# editing this list. The engines' internals (sim/engines/src) stay private.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/sim/model/include/" "${PROJECT_SOURCE_DIR}/sim/io/include/"
                  "${PROJECT_SOURCE_DIR}/sim/engines/include/" "${PROJECT_SOURCE_DIR}/sim/run/include/"
                  "${PROJECT_SOURCE_DIR}/sim/tail/include/" "${PROJECT_SOURCE_DIR}/sim/ranks/include/"
                  "${PROJECT_SOURCE_DIR}/sim/spheres/include/"
                  "${PROJECT_SOURCE_DIR}/analysis/include/"
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev
        FILES_MATCHING PATTERN "*.hpp")

# The CMake package.
install(EXPORT shockgasTargets
        NAMESPACE shockgas::
        DESTINATION ${SHOCKGAS_INSTALL_CMAKEDIR}
        COMPONENT dev)
install(EXPORT shockgasPrograms
        NAMESPACE shockgas::
        DESTINATION ${SHOCKGAS_INSTALL_CMAKEDIR}
        COMPONENT runtime)
configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/shockgasConfig.cmake.in"
                              "${PROJECT_BINARY_DIR}/shockgasConfig.cmake"
                              INSTALL_DESTINATION ${SHOCKGAS_INSTALL_CMAKEDIR})
# 0.x: a new minor version may break the interface, so only 0.2.* satisfies 0.2.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/shockgasConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/shockgasConfig.cmake" "${PROJECT_BINARY_DIR}/shockgasConfigVersion.cmake"
        DESTINATION ${SHOCKGAS_INSTALL_CMAKEDIR} COMPONENT dev)

# The figure pipeline, as a project of its own that runs the installed
# programs: cmake -S <prefix>/share/shockgas -B figs && cmake --build figs --target fig3.
# Its layout mirrors the source tree's, so the pipeline's paths are the same.
file(RELATIVE_PATH SHOCKGAS_PROGRAMS_FROM_DATADIR "/${SHOCKGAS_INSTALL_DATADIR}" "/${SHOCKGAS_INSTALL_CMAKEDIR}")
configure_file("${PROJECT_SOURCE_DIR}/cmake/installed-pipeline/CMakeLists.txt.in"
               "${PROJECT_BINARY_DIR}/installed-pipeline/CMakeLists.txt" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/installed-pipeline/CMakeLists.txt"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR} COMPONENT runtime)
install(FILES "${PROJECT_SOURCE_DIR}/cmake/ShockgasPython.cmake" "${PROJECT_SOURCE_DIR}/cmake/ShortestNumber.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/RunSimulation.cmake"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/cmake COMPONENT runtime)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/paper_targets/"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/paper_targets COMPONENT runtime
        FILES_MATCHING PATTERN "*.json" PATTERN "*.cmake" PATTERN "CMakeLists.txt"
                       PATTERN "archive.cmake" EXCLUDE)  # archives need the git source
install(DIRECTORY "${PROJECT_SOURCE_DIR}/figures/"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/figures COMPONENT runtime
        FILES_MATCHING PATTERN "*.gp")
install(PROGRAMS "${PROJECT_SOURCE_DIR}/python/exact_ballistic.py" "${PROJECT_SOURCE_DIR}/python/sticky_pav.py"
                 "${PROJECT_SOURCE_DIR}/python/refit_check.py" "${PROJECT_SOURCE_DIR}/python/reference_gas.py"
                 "${PROJECT_SOURCE_DIR}/python/clusters_check.py" "${PROJECT_SOURCE_DIR}/python/tails_check.py"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/python COMPONENT runtime)
# shockgas-look finds figures/look.gp and style.gp in ../share/shockgas/figures.
install(PROGRAMS "${PROJECT_SOURCE_DIR}/tools/shockgas-look" DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(PROGRAMS "${PROJECT_SOURCE_DIR}/tools/fidelity_report.py" "${PROJECT_SOURCE_DIR}/tools/reproduce-check"
        DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/tools COMPONENT runtime)
# How those two find the module (beside them, as in the source tree).
install(FILES "${PROJECT_SOURCE_DIR}/tools/shockgas_path.py" DESTINATION ${SHOCKGAS_INSTALL_DATADIR}/tools
        COMPONENT runtime)

# The Python module `shockgas`, into the prefix's own module folder, chosen at
# install time (the prefix can be changed by `cmake --install --prefix` and is
# /usr inside a Debian package).
if(SHOCKGAS_PYTHON)
  execute_process(COMMAND "${SHOCKGAS_PYTHON}" -c
                          "import sys, sysconfig; print('%d.%d' % sys.version_info[:2]); print(int('deb_system' in sysconfig.get_scheme_names()))"
                  OUTPUT_VARIABLE _shockgas_python_facts OUTPUT_STRIP_TRAILING_WHITESPACE)
  string(REPLACE "\n" ";" _shockgas_python_facts "${_shockgas_python_facts}")
  list(GET _shockgas_python_facts 0 SHOCKGAS_PYTHON_VERSION)
  list(GET _shockgas_python_facts 1 SHOCKGAS_PYTHON_IS_DEBIAN)
else()
  set(SHOCKGAS_PYTHON_VERSION 3)
  set(SHOCKGAS_PYTHON_IS_DEBIAN 0)
endif()
set(SHOCKGAS_INSTALL_PYTHONDIR "" CACHE STRING
    "Where the Python module goes (relative to the prefix, or absolute); empty: the prefix's own module folder")
install(CODE "
  set(SHOCKGAS_MODULE_SOURCE \"${PROJECT_SOURCE_DIR}/python/shockgas\")
  set(SHOCKGAS_INSTALL_PYTHONDIR \"${SHOCKGAS_INSTALL_PYTHONDIR}\")
  set(SHOCKGAS_PYTHON_VERSION \"${SHOCKGAS_PYTHON_VERSION}\")
  set(SHOCKGAS_PYTHON_IS_DEBIAN \"${SHOCKGAS_PYTHON_IS_DEBIAN}\")
  include(\"${PROJECT_SOURCE_DIR}/cmake/InstallPythonModule.cmake\")"
  COMPONENT runtime)

# The licence (GPL-3.0-or-later) with each package, as Debian's policy asks: the
# full text as LICENSE and the machine-readable copyright file.
install(FILES LICENSE cmake/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
install(FILES LICENSE cmake/copyright DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/shockgas-dev COMPONENT dev)

# Documentation, with the relative links between the pages kept.
install(FILES README.md ARCHITECTURE.md CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/docs/" DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs COMPONENT runtime
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png" PATTERN "*.svg")
install(FILES analysis/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}/analysis COMPONENT runtime)

include(ManPages)

# What cmake/InstallCheck.cmake looks for: the files the rules above take from the build tree.
set(_install_needs)
foreach(library IN LISTS SHOCKGAS_LIBRARIES)
  string(APPEND _install_needs "dev\t$<TARGET_FILE:${library}>\n")
endforeach()
foreach(program IN LISTS SHOCKGAS_PROGRAMS)
  string(APPEND _install_needs "runtime\t$<TARGET_FILE:${program}>\n")
endforeach()
foreach(page IN LISTS SHOCKGAS_MAN_PAGE_FILES)
  string(APPEND _install_needs "runtime\t${page}\n")
endforeach()
file(GENERATE OUTPUT "${PROJECT_BINARY_DIR}/install-needs.txt" CONTENT "${_install_needs}")
