# SPDX-License-Identifier: GPL-3.0-or-later
# Run by `cmake --install` and cpack (install(CODE) in cmake/Install.cmake):
# copies python/shockgas into the module folder that the installation
# prefix's Python reads, decided now because the prefix may differ from the
# configured one (`cmake --install --prefix ~/.local`; /usr in a .deb).
#   SHOCKGAS_INSTALL_PYTHONDIR set         that folder (relative to the prefix, or absolute)
#   /usr with Debian's Python              lib/python3/dist-packages        (Debian's own packages)
#   /usr/local with Debian's Python        lib/python3.X/dist-packages      (on Debian's sys.path)
#   any other prefix                       lib/python3.X/site-packages      (Python's posix_prefix
#                                          layout; ~/.local/... is the user site, on sys.path)
if(SHOCKGAS_INSTALL_PYTHONDIR)
  set(_module_dir "${SHOCKGAS_INSTALL_PYTHONDIR}")
elseif(CMAKE_INSTALL_PREFIX STREQUAL "/usr" AND SHOCKGAS_PYTHON_IS_DEBIAN)
  set(_module_dir "lib/python3/dist-packages")
elseif(CMAKE_INSTALL_PREFIX STREQUAL "/usr/local" AND SHOCKGAS_PYTHON_IS_DEBIAN)
  set(_module_dir "lib/python${SHOCKGAS_PYTHON_VERSION}/dist-packages")
else()
  set(_module_dir "lib/python${SHOCKGAS_PYTHON_VERSION}/site-packages")
endif()
if(NOT IS_ABSOLUTE "${_module_dir}")
  set(_module_dir "${CMAKE_INSTALL_PREFIX}/${_module_dir}")
endif()
file(INSTALL DESTINATION "${_module_dir}" TYPE DIRECTORY FILES "${SHOCKGAS_MODULE_SOURCE}"
     FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
message(STATUS "Python module shockgas: ${_module_dir}/shockgas (import shockgas; "
               "outside Python's own folders: PYTHONPATH=${_module_dir})")
