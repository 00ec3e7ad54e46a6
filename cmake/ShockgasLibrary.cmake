# SPDX-License-Identifier: GPL-3.0-or-later
# shockgas_library(<role> SOURCES <files...> [PUBLIC <targets...>] [PRIVATE <targets...>])
# One room's library: target shockgas_<role>, used as shockgas::<role> (here and,
# installed, through find_package(shockgas)), its public headers in the room's
# include/ folder (installed as include/shockgas/<role>/), our warnings for
# building only. Dependencies are imported targets, not paths, so that the
# exported package finds them again on the user's machine.
function(shockgas_library role)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(shockgas_${role} ${ARG_SOURCES})
  add_library(shockgas::${role} ALIAS shockgas_${role})
  set_target_properties(shockgas_${role} PROPERTIES EXPORT_NAME ${role})
  target_include_directories(shockgas_${role} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                     $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(shockgas_${role} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE} $<BUILD_INTERFACE:shockgas_warnings>)
endfunction()
