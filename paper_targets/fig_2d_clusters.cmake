# SPDX-License-Identifier: GPL-3.0-or-later
# Clusters of the 2D gas of fig_2d (its runs, no run of its own; docs/dimensions.md): density
# maps of the eps = 0.1 run, and the largest cluster and the mass distribution against the
# paper's critical size N_c ~ eps^-2.
set(fig_2d_clusters_DIR "${CMAKE_CURRENT_BINARY_DIR}/${SHOCKGAS_FIDELITY}/fig_2d_clusters")
file(MAKE_DIRECTORY "${fig_2d_clusters_DIR}")
set(_clusters_inputs)
foreach(run IN LISTS fig_2d_RUNS)
  list(APPEND _clusters_inputs "${fig_2d_${run}_H5}")
endforeach()
set(_clusters_base "${fig_2d_clusters_DIR}/clusters")
shockgas_step(
  OUTPUT "${_clusters_base}.h5" "${_clusters_base}.dat" "${_clusters_base}.masses.dat" "${_clusters_base}.maps.dat"
  COMMAND shockgas-analyze clusters ${_clusters_inputs} -o "${_clusters_base}.h5" --data "${_clusters_base}.dat"
          --distribution "${_clusters_base}.masses.dat" --maps "${_clusters_base}.maps.dat"
  DEPENDS ${_clusters_inputs} shockgas-analyze
  COMMENT "[fig_2d_clusters] clusters of the density field"
  VERBATIM)
shockgas_step(
  OUTPUT "${_clusters_base}.fit.gp"
  COMMAND shockgas-dump gnuplot-vars "${_clusters_base}.h5" / --recursive --prefix cl --output "${_clusters_base}.fit.gp"
  DEPENDS "${_clusters_base}.h5" shockgas-dump
  COMMENT "[fig_2d_clusters] the cluster numbers for gnuplot"
  VERBATIM)
shockgas_plot(fig_2d_clusters SCRIPT fig_2d_clusters.gp
              DATA "${_clusters_base}.dat" "${_clusters_base}.masses.dat" "${_clusters_base}.maps.dat"
                   "${_clusters_base}.fit.gp")
# fig_2d's runs are its custom commands' outputs: fig_2d builds them first, or a parallel Makefile
# build would start each run twice (once for each target), and the second would find the first's
# checkpoint locked.
add_dependencies(fig_2d_clusters fig_2d)
