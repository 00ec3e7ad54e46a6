# SPDX-License-Identifier: GPL-3.0-or-later
# t_dissip, t_stick and T(t_stick) against eps, with power-law fits against the
# predicted -1, -3/2 and +1 (Eq. 3 and the text around Fig. 1).
shockgas_figure_runs(fig_crossovers)
set(_crossover_inputs)
foreach(run IN LISTS fig_crossovers_RUNS)
  list(APPEND _crossover_inputs "${fig_crossovers_${run}_H5}")
endforeach()
set(_dir "${fig_crossovers_DIR}")
shockgas_step(
  OUTPUT "${_dir}/crossovers.dat" "${_dir}/crossovers.h5" "${_dir}/crossovers.gp"
  COMMAND shockgas-analyze crossover ${_crossover_inputs} -o "${_dir}/crossovers.h5" --data "${_dir}/crossovers.dat"
  COMMAND shockgas-dump gnuplot-vars "${_dir}/crossovers.h5" /scaling_in_eps --prefix fit --output "${_dir}/crossovers.gp"
  DEPENDS ${_crossover_inputs} shockgas-analyze shockgas-dump
  COMMENT "[fig_crossovers] crossover times"
  VERBATIM)
shockgas_plot(fig_crossovers SCRIPT fig_crossovers.gp DATA "${_dir}/crossovers.dat" "${_dir}/crossovers.gp")
