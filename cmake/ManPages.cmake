# SPDX-License-Identifier: GPL-3.0-or-later
# Man pages made from each program's --help (and --version) by Debian's
# help2man at build time, so they cannot disagree with the programs; installed
# to share/man/man1, compressed as Debian's policy asks (gzip -9n: no name or
# time stamp in the archive). -DSHOCKGAS_MAN_PAGES=OFF builds without help2man.
option(SHOCKGAS_MAN_PAGES "Make man pages with help2man (tools/install-deps.sh installs it)" ON)
if(NOT SHOCKGAS_MAN_PAGES)
  return()
endif()
find_program(HELP2MAN_EXECUTABLE help2man)
find_program(GZIP_EXECUTABLE gzip REQUIRED)
if(NOT HELP2MAN_EXECUTABLE)
  message(FATAL_ERROR "help2man not found: run tools/install-deps.sh (Debian package help2man), "
                      "or configure with -DSHOCKGAS_MAN_PAGES=OFF")
endif()

# One line each: the NAME section of the man page.
set(_shockgas-sim_name "event-driven simulation of a one-dimensional inelastic gas on a ring")
set(_shockgas-merge_name "join ensemble parts of a shockgas-sim run into one output file")
set(_shockgas-dump_name "shockgas HDF5 files as plain text for gnuplot")
set(_shockgas-burgers_name "Burgers-equation profiles from a shockgas run's initial condition")
set(_shockgas-analyze_name "estimators and fits on shockgas-sim output")
set(_shockgas-tail_name "far tail of the sticky gas velocity distribution by biased Markov chains")
set(_shockgas-plan_name "the cheapest threshold delta the validity map says keeps an observable as in the sticky gas")
set(_shockgas-spheres_name "inelastic hard disks and spheres with the threshold rule, event-driven")
# Programs with subcommands print every subcommand's options with --help-all.
set(_shockgas-dump_help --help-all)
set(_shockgas-analyze_help --help-all)

set(_man_dir "${PROJECT_BINARY_DIR}/man")
file(MAKE_DIRECTORY "${_man_dir}")
# SEE ALSO and the documentation's whereabouts, shared by every page.
list(TRANSFORM SHOCKGAS_PROGRAMS APPEND "(1)" OUTPUT_VARIABLE _see_also)
list(JOIN _see_also ", " _see_also)
file(CONFIGURE OUTPUT "${_man_dir}/see_also.h2m" CONTENT "[SEE ALSO]
${_see_also}.
.PP
The documentation (README.md and docs/: the output schema, checkpoints and MPI, the engines,
the paper's targets) is installed in share/doc/shockgas under the installation prefix.
The Python module \\fBshockgas\\fR reads every file these programs write.
" @ONLY)

set(_man_pages)
foreach(program IN LISTS SHOCKGAS_PROGRAMS)
  set(page "${_man_dir}/${program}.1")
  set(help_option --help)
  if(DEFINED _${program}_help)
    set(help_option ${_${program}_help})
  endif()
  add_custom_command(
    OUTPUT "${page}.gz"
    COMMAND ${HELP2MAN_EXECUTABLE} --no-info "--name=${_${program}_name}"
            "--help-option=${help_option}" --version-option=--version
            "--include=${_man_dir}/see_also.h2m" "--output=${page}" $<TARGET_FILE:${program}>
    COMMAND ${GZIP_EXECUTABLE} -9nf "${page}"
    DEPENDS ${program} "${_man_dir}/see_also.h2m"
    COMMENT "Man page ${program}.1 from ${program} ${help_option}"
    VERBATIM)
  list(APPEND _man_pages "${page}.gz")
endforeach()
add_custom_target(man_pages ALL DEPENDS ${_man_pages})
# The README's first build makes only the figures (`--target figures`), which need every program
# already; the pages come with them (help2man runs each program's --help, about a second), so that
# `cmake --install` works from that build as from a full one.
if(TARGET figures)
  add_dependencies(figures man_pages)
endif()
set(SHOCKGAS_MAN_PAGE_FILES ${_man_pages})  # for cmake/Install.cmake's check before installing
install(FILES ${_man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
