# SPDX-License-Identifier: GPL-3.0-or-later
# Run by `cmake --install` and cpack before any other install rule (install(CODE) at the top of
# cmake/Install.cmake): every file the installation takes from the build tree must be there.
# A tree built only in part (one program, or no man pages) is refused with the files it lacks and
# the command that makes them, before anything is copied; otherwise the install would stop at the
# first missing file with a prefix half filled.
# SHOCKGAS_BUILD_DIR: the build tree. Its install-needs.txt (written at generate time by
# cmake/Install.cmake) has one line per built file: "<component>\t<path>".
file(STRINGS "${SHOCKGAS_BUILD_DIR}/install-needs.txt" _shockgas_needs)
set(_shockgas_missing)
foreach(_line IN LISTS _shockgas_needs)
  string(REGEX MATCH "^([^\t]*)\t(.*)$" _ "${_line}")
  set(_component "${CMAKE_MATCH_1}")
  set(_path "${CMAKE_MATCH_2}")
  # One component at a time (cpack, --component) needs only that component's files.
  if(CMAKE_INSTALL_COMPONENT AND NOT CMAKE_INSTALL_COMPONENT STREQUAL _component)
    continue()
  endif()
  if(NOT EXISTS "${_path}")
    file(RELATIVE_PATH _path "${SHOCKGAS_BUILD_DIR}" "${_path}")
    list(APPEND _shockgas_missing "${_path}")
  endif()
endforeach()
if(_shockgas_missing)
  list(JOIN _shockgas_missing ", " _shockgas_missing)
  message(FATAL_ERROR "shockgas: nothing installed: ${SHOCKGAS_BUILD_DIR} lacks ${_shockgas_missing}; "
                      "build it first (cmake --build ${SHOCKGAS_BUILD_DIR}), then install again")
endif()
