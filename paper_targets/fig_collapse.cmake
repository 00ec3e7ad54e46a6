# SPDX-License-Identifier: GPL-3.0-or-later
# Inelastic collapse (delta = 0) against eps and N
# (docs/haff-and-collapse.md): collapse time and cluster mass per eps with the
# competing forms fitted, and first-collapse statistics across N at one eps.
# Runs named eps* make the eps sweep, runs named N* the N series.
shockgas_figure_runs(fig_collapse)
set(_eps_inputs)
set(_n_inputs)
foreach(run IN LISTS fig_collapse_RUNS)
  if(run MATCHES "^eps")
    list(APPEND _eps_inputs "${fig_collapse_${run}_H5}")
  elseif(run MATCHES "^N")
    list(APPEND _n_inputs "${fig_collapse_${run}_H5}")
  else()
    message(FATAL_ERROR "fig_collapse: run '${run}' is neither eps* (the eps sweep) nor N* (the N series)")
  endif()
endforeach()
set(_dir "${fig_collapse_DIR}")
shockgas_step(
  OUTPUT "${_dir}/vs_eps.dat" "${_dir}/vs_eps.h5" "${_dir}/time_forms.gp" "${_dir}/mass_forms.gp"
  COMMAND shockgas-analyze collapse --vs eps ${_eps_inputs} -o "${_dir}/vs_eps.h5" --data "${_dir}/vs_eps.dat"
  COMMAND shockgas-dump gnuplot-vars "${_dir}/vs_eps.h5" /time_forms --recursive --prefix time
          --output "${_dir}/time_forms.gp"
  COMMAND shockgas-dump gnuplot-vars "${_dir}/vs_eps.h5" /mass_forms --recursive --prefix mass
          --output "${_dir}/mass_forms.gp"
  DEPENDS ${_eps_inputs} shockgas-analyze shockgas-dump
  COMMENT "[fig_collapse] collapse time and mass against eps: competing forms"
  VERBATIM)
shockgas_step(
  OUTPUT "${_dir}/vs_N.dat" "${_dir}/vs_N.h5" "${_dir}/vs_N.gp" "${_dir}/hazard.dat"
  COMMAND shockgas-analyze collapse --vs N ${_n_inputs} -o "${_dir}/vs_N.h5" --data "${_dir}/vs_N.dat"
          --hazard "${_dir}/hazard.dat"
  COMMAND shockgas-dump gnuplot-vars "${_dir}/vs_N.h5" /first_collapse --prefix fit --output "${_dir}/vs_N.gp"
  DEPENDS ${_n_inputs} shockgas-analyze shockgas-dump
  COMMENT "[fig_collapse] first-collapse statistics across N"
  VERBATIM)
shockgas_plot(fig_collapse SCRIPT fig_collapse.gp
              DATA "${_dir}/vs_eps.dat" "${_dir}/time_forms.gp" "${_dir}/mass_forms.gp" "${_dir}/vs_N.dat" "${_dir}/vs_N.gp" "${_dir}/hazard.dat")
