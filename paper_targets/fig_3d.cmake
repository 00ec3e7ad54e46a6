# SPDX-License-Identifier: GPL-3.0-or-later
# The paper's d-dimensional prediction in d = 3 (docs/dimensions.md): shockgas-spheres runs at
# several eps, one late-decay analysis of all of them (theta, the crossover against eps, the
# kurtosis, Delta v / v), one plot (figures/fig_3d.gp, drawn by figures/late_decay.gp).
shockgas_figure_runs(fig_3d)
set(_late_inputs_3)
foreach(run IN LISTS fig_3d_RUNS)
  list(APPEND _late_inputs_3 "${fig_3d_${run}_H5}")
endforeach()
set(_late_base "${fig_3d_DIR}/late")
shockgas_step(
  OUTPUT "${_late_base}.h5" "${_late_base}.T.dat" "${_late_base}.slopes.dat" "${_late_base}.crossovers.dat"
         "${_late_base}.dv.dat"
  COMMAND shockgas-analyze late-decay ${_late_inputs_3} -o "${_late_base}.h5" --data "${_late_base}.T.dat"
          --slopes "${_late_base}.slopes.dat" --crossovers "${_late_base}.crossovers.dat"
          --fluctuations "${_late_base}.dv.dat"
  DEPENDS ${_late_inputs_3} shockgas-analyze
  COMMENT "[fig_3d] late decay: theta, crossover against eps, Delta v / v"
  VERBATIM)
shockgas_step(
  OUTPUT "${_late_base}.fit.gp"
  COMMAND shockgas-dump gnuplot-vars "${_late_base}.h5" / --recursive --prefix ld --output "${_late_base}.fit.gp"
  DEPENDS "${_late_base}.h5" shockgas-dump
  COMMENT "[fig_3d] the fitted numbers for gnuplot"
  VERBATIM)
shockgas_plot(fig_3d SCRIPT fig_3d.gp
              DATA "${_late_base}.T.dat" "${_late_base}.slopes.dat" "${_late_base}.crossovers.dat"
                   "${_late_base}.dv.dat" "${_late_base}.fit.gp" "${PROJECT_SOURCE_DIR}/figures/late_decay.gp")
