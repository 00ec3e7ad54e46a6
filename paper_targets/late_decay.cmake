# SPDX-License-Identifier: GPL-3.0-or-later
# shockgas_late_decay_figure(<figure>): a figure of the paper's d-dimensional prediction
# (fig_2d, fig_3d; docs/dimensions.md): its shockgas-spheres runs at several eps, one late-decay
# analysis of all of them (theta, the crossover against eps, the kurtosis, Delta v / v, the
# velocity distribution's tails), the
# fitted numbers for gnuplot, and the plot (figures/<figure>.gp, drawn by figures/late_decay.gp).
include_guard(GLOBAL)
function(shockgas_late_decay_figure figure)
  shockgas_figure_runs(${figure})
  set(inputs)
  foreach(run IN LISTS ${figure}_RUNS)
    list(APPEND inputs "${${figure}_${run}_H5}")
  endforeach()
  set(base "${${figure}_DIR}/late")
  shockgas_step(
    OUTPUT "${base}.h5" "${base}.T.dat" "${base}.slopes.dat" "${base}.crossovers.dat" "${base}.dv.dat"
           "${base}.tails.dat" "${base}.tail_fits.dat"
    COMMAND shockgas-analyze late-decay ${inputs} -o "${base}.h5" --data "${base}.T.dat"
            --slopes "${base}.slopes.dat" --crossovers "${base}.crossovers.dat" --fluctuations "${base}.dv.dat"
            --tails "${base}.tails.dat" --tail-fits "${base}.tail_fits.dat"
    DEPENDS ${inputs} shockgas-analyze
    COMMENT "[${figure}] late decay: theta, crossover against eps, Delta v / v, velocity tails"
    VERBATIM)
  shockgas_gnuplot_vars(${figure} "${base}.h5" ld "${base}.fit.gp")
  shockgas_plot(${figure} SCRIPT ${figure}.gp
                DATA "${base}.T.dat" "${base}.slopes.dat" "${base}.crossovers.dat" "${base}.dv.dat"
                     "${base}.tails.dat" "${base}.tail_fits.dat" "${base}.fit.gp"
                     "${PROJECT_SOURCE_DIR}/figures/late_decay.gp")
  # The runs' outputs, for figures that analyse them too (fig_2d_clusters, fig_3d_clusters).
  set(${figure}_RUNS "${${figure}_RUNS}" PARENT_SCOPE)
  foreach(run IN LISTS ${figure}_RUNS)
    set(${figure}_${run}_H5 "${${figure}_${run}_H5}" PARENT_SCOPE)
  endforeach()
endfunction()
