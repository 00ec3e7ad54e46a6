# SPDX-License-Identifier: GPL-3.0-or-later
# cpack -G DEB (run in the build directory) writes two Debian packages:
#   shockgas      the programs, the Python module, the figure project, man pages and docs
#   shockgas-dev  headers, static libraries and the CMake package (find_package(shockgas))
# Library dependencies of the programs are computed by dpkg-shlibdeps; the rest
# are declared here, by Debian package name.
set(CPACK_PACKAGE_NAME shockgas)
set(CPACK_PACKAGE_VENDOR "shockgas")
set(CPACK_PACKAGE_CONTACT "shockgas maintainers <shockgas@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "Reproduces E. Ben-Naim, S. Y. Chen, G. D. Doolen and S. Redner, Shock-Like Dynamics of Inelastic Gases, "
    "Phys. Rev. Lett. 83, 4069 (1999): an event-driven simulator of a one-dimensional inelastic gas on a ring "
    "writing HDF5 (shockgas-sim), estimators and fits (shockgas-analyze), a Python reader for every file, and "
    "a CMake project that remakes the paper's figures from the installed programs.")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_INSTALL_DIRECTORY shockgas)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_FILE_NAME "shockgas-${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)

set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://doi.org/10.1103/PhysRevLett.83.4069")
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)  # shockgas-dev: Depends: shockgas (= version)

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME shockgas)
# libhdf5, libgsl, libfmt, libstdc++ (and libopenmpi for an MPI build): from the ELF files.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# The Python module reads with numpy and h5py.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "python3, python3-numpy, python3-h5py")
if(SHOCKGAS_MPI)
  string(APPEND CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS ", openmpi-bin")
endif()
# Remaking the figures from the installed copy (share/shockgas): CMake and make,
# gnuplot, scipy for the exact-theory curves.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "cmake, make, gnuplot-nox, python3-scipy")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME shockgas-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "libhdf5-dev, libfmt-dev, libgsl-dev, libssl-dev")
if(SHOCKGAS_MPI)
  string(APPEND CPACK_DEBIAN_DEV_PACKAGE_DEPENDS ", libopenmpi-dev")
endif()
set(CPACK_DEBIAN_DEV_PACKAGE_RECOMMENDS "cmake, g++")
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)

include(CPack)
cpack_add_component(runtime DISPLAY_NAME "shockgas programs, Python module, figures project, man pages, docs")
cpack_add_component(dev DISPLAY_NAME "shockgas headers, static libraries and CMake package" DEPENDS runtime)
