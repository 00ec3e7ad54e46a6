# SPDX-License-Identifier: GPL-3.0-or-later
# Homogeneous cooling of inelastic disks and spheres on Haff's law and the start
# of clustering (docs/spheres.md): shockgas-spheres runs, one cooling analysis of
# all four, one plot.
shockgas_figure_runs(fig_spheres)
set(_spheres_inputs)
foreach(run IN LISTS fig_spheres_RUNS)
  list(APPEND _spheres_inputs "${fig_spheres_${run}_H5}")
endforeach()
set(_spheres_base "${fig_spheres_DIR}/cooling")
shockgas_step(
  OUTPUT "${_spheres_base}.h5" "${_spheres_base}.T.dat" "${_spheres_base}.clustering.dat" "${_spheres_base}.picture.dat"
  COMMAND shockgas-analyze cooling ${_spheres_inputs} -o "${_spheres_base}.h5" --data "${_spheres_base}.T.dat"
          --clustering "${_spheres_base}.clustering.dat" --picture "${_spheres_base}.picture.dat"
  DEPENDS ${_spheres_inputs} shockgas-analyze
  COMMENT "[fig_spheres] cooling against Haff's law, clustering"
  VERBATIM)
shockgas_plot(fig_spheres SCRIPT fig_spheres.gp
              DATA "${_spheres_base}.T.dat" "${_spheres_base}.clustering.dat" "${_spheres_base}.picture.dat")
