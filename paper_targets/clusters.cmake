# SPDX-License-Identifier: GPL-3.0-or-later
# shockgas_clusters_figure(<figure> <source figure> [MAPS]): the clusters of the density field of the
# source figure's runs (its runs, no run of its own; docs/dimensions.md), from shockgas-analyze
# clusters: the largest cluster and the mass distribution against the paper's critical size scale
# N_c ~ eps^(-2d/(4-d)), and with MAPS (2D runs only: shockgas-analyze refuses --maps in 3D) density
# maps of the first run's realization 0 (figures/clusters.gp draws them when they are there).
# fig_2d_clusters (fig_2d's disks) and fig_3d_clusters (fig_3d's spheres).
function(shockgas_clusters_figure figure source)
  cmake_parse_arguments(ARG "MAPS" "" "" ${ARGN})
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/${SHOCKGAS_FIDELITY}/${figure}")
  file(MAKE_DIRECTORY "${dir}")
  set(inputs)
  foreach(run IN LISTS ${source}_RUNS)
    list(APPEND inputs "${${source}_${run}_H5}")
  endforeach()
  set(base "${dir}/clusters")
  if(ARG_MAPS)
    set(maps "${base}.maps.dat")
    set(maps_option --maps "${maps}")
  else()
    set(maps)
    set(maps_option)
  endif()
  shockgas_step(
    OUTPUT "${base}.h5" "${base}.dat" "${base}.masses.dat" ${maps}
    COMMAND shockgas-analyze clusters ${inputs} -o "${base}.h5" --data "${base}.dat"
            --distribution "${base}.masses.dat" ${maps_option}
    DEPENDS ${inputs} shockgas-analyze
    COMMENT "[${figure}] clusters of the density field"
    VERBATIM)
  shockgas_gnuplot_vars(${figure} "${base}.h5" cl "${base}.fit.gp")
  shockgas_plot(${figure} SCRIPT clusters.gp DATA "${base}.dat" "${base}.masses.dat" ${maps} "${base}.fit.gp")
  # The source's runs are its custom commands' outputs: the source figure builds them first, or a
  # parallel Makefile build would start each run twice (once for each target), and the second would
  # find the first's checkpoint locked.
  add_dependencies(${figure} ${source})
endfunction()
