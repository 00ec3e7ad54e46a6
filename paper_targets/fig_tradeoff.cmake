# SPDX-License-Identifier: GPL-3.0-or-later
# The speed/accuracy trade (docs/figures-and-fidelity.md): cost and accuracy of the threshold delta
# and of the sub-threshold mechanism against the most accurate run (delta =
# 1e-4, elastic), and the decay exponent's statistical error against CPU.
shockgas_figure_runs(fig_tradeoff)
set(_dir "${fig_tradeoff_DIR}")
# Reference: the smallest delta, elastic when the fidelity affords it
# (paper), sticky otherwise (quick).
if(DEFINED fig_tradeoff_d1e-4_elastic_H5)
  set(_reference_run d1e-4_elastic)
else()
  set(_reference_run d1e-4_sticky)
endif()
set(_reference "${fig_tradeoff_${_reference_run}_H5}")
set(_compared)
set(_stat_outputs)
foreach(run IN LISTS fig_tradeoff_RUNS)
  if(run MATCHES "^stat_")
    # Short gnuplot prefix (gnuplot truncates long variable names): stat_N1000_R4 -> s1000r4.
    string(REPLACE "stat_N" "s" id "${run}")
    string(REPLACE "_R" "r" id "${id}")
    shockgas_step(
      OUTPUT "${_dir}/${run}.decay.h5" "${_dir}/${run}.fit.gp"
      COMMAND shockgas-analyze decay "${fig_tradeoff_${run}_H5}" -o "${_dir}/${run}.decay.h5"
      COMMAND shockgas-dump gnuplot-vars "${_dir}/${run}.decay.h5" / --recursive --prefix "${id}"
              --output "${_dir}/${run}.fit.gp"
      DEPENDS "${fig_tradeoff_${run}_H5}" shockgas-analyze shockgas-dump
      COMMENT "[fig_tradeoff] exponent and its error: ${run}"
      VERBATIM)
    list(APPEND _stat_outputs "${_dir}/${run}.fit.gp")
  elseif(NOT run STREQUAL _reference_run)
    list(APPEND _compared "${fig_tradeoff_${run}_H5}")
  endif()
endforeach()
shockgas_step(
  OUTPUT "${_dir}/tradeoff.dat" "${_dir}/deviation.dat" "${_dir}/tradeoff.h5" "${_dir}/reference.gp"
  COMMAND shockgas-analyze compare "${_reference}" ${_compared} -o "${_dir}/tradeoff.h5"
          --data "${_dir}/tradeoff.dat" --curves "${_dir}/deviation.dat"
  COMMAND shockgas-dump gnuplot-vars "${_reference}" / --prefix reference --output "${_dir}/reference.gp"
  DEPENDS "${_reference}" ${_compared} shockgas-analyze shockgas-dump
  COMMENT "[fig_tradeoff] deviations from ${_reference_run}"
  VERBATIM)
shockgas_plot(fig_tradeoff SCRIPT fig_tradeoff.gp DATA "${_dir}/tradeoff.dat" "${_dir}/deviation.dat"
              "${_dir}/reference.gp" ${_stat_outputs})
