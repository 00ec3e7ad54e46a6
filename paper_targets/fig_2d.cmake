# SPDX-License-Identifier: GPL-3.0-or-later
# The paper's d-dimensional prediction in d = 2 (docs/dimensions.md): shockgas-spheres runs at
# several eps, one late-decay analysis of all of them (theta, the crossover against eps, the
# kurtosis, Delta v / v), one plot (figures/fig_2d.gp, drawn by figures/late_decay.gp).
shockgas_figure_runs(fig_2d)
set(_late_inputs_2)
foreach(run IN LISTS fig_2d_RUNS)
  list(APPEND _late_inputs_2 "${fig_2d_${run}_H5}")
endforeach()
set(_late_base "${fig_2d_DIR}/late")
shockgas_step(
  OUTPUT "${_late_base}.h5" "${_late_base}.T.dat" "${_late_base}.slopes.dat" "${_late_base}.crossovers.dat"
         "${_late_base}.dv.dat"
  COMMAND shockgas-analyze late-decay ${_late_inputs_2} -o "${_late_base}.h5" --data "${_late_base}.T.dat"
          --slopes "${_late_base}.slopes.dat" --crossovers "${_late_base}.crossovers.dat"
          --fluctuations "${_late_base}.dv.dat"
  DEPENDS ${_late_inputs_2} shockgas-analyze
  COMMENT "[fig_2d] late decay: theta, crossover against eps, Delta v / v"
  VERBATIM)
shockgas_step(
  OUTPUT "${_late_base}.fit.gp"
  COMMAND shockgas-dump gnuplot-vars "${_late_base}.h5" / --recursive --prefix ld --output "${_late_base}.fit.gp"
  DEPENDS "${_late_base}.h5" shockgas-dump
  COMMENT "[fig_2d] the fitted numbers for gnuplot"
  VERBATIM)
shockgas_plot(fig_2d SCRIPT fig_2d.gp
              DATA "${_late_base}.T.dat" "${_late_base}.slopes.dat" "${_late_base}.crossovers.dat"
                   "${_late_base}.dv.dat" "${_late_base}.fit.gp" "${PROJECT_SOURCE_DIR}/figures/late_decay.gp")
