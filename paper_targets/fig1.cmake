# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 1: T(t) for r = 0, 0.5, 0.9, 0.99 with delta = 1e-2, and the pure
# inelastic gas (delta = 0) as dots that stop at collapse. Each delta > 0 curve
# gets the decay exponent fitted over the automatic post-crossover window.
shockgas_figure_runs(fig1)
set(_fig1_data ${SHOCKGAS_THEORY_DIR}/constants.gp)
set(_fig1_results)
foreach(run IN LISTS fig1_RUNS)
  set(h5 "${fig1_${run}_H5}")
  set(base "${fig1_DIR}/${run}")
  string(MAKE_C_IDENTIFIER "${run}" id)
  if(run MATCHES "^pure_")
    shockgas_step(
      OUTPUT "${base}.T.dat" "${base}.collapse.h5" "${base}.collapse.dat"
      COMMAND shockgas-analyze decay "${h5}" --data-only --data "${base}.T.dat"
      COMMAND shockgas-analyze collapse "${h5}" -o "${base}.collapse.h5" --data "${base}.collapse.dat"
      DEPENDS "${h5}" shockgas-analyze
      COMMENT "[fig1] T(t) until collapse: ${run}"
      VERBATIM)
    list(APPEND _fig1_data "${base}.T.dat" "${base}.collapse.dat")
  else()
    shockgas_step(
      OUTPUT "${base}.T.dat" "${base}.scan.dat" "${base}.decay.h5" "${base}.fit.gp"
      COMMAND shockgas-analyze decay "${h5}" -o "${base}.decay.h5" --data "${base}.T.dat" --scan "${base}.scan.dat"
      COMMAND shockgas-dump gnuplot-vars "${base}.decay.h5" /decay --prefix "fit_${id}" --output "${base}.fit.gp"
      DEPENDS "${h5}" shockgas-analyze shockgas-dump
      COMMENT "[fig1] decay exponent: ${run}"
      VERBATIM)
    list(APPEND _fig1_data "${base}.T.dat" "${base}.fit.gp")
    list(APPEND _fig1_results "${base}.decay.h5")
  endif()
endforeach()
shockgas_plot(fig1 SCRIPT fig1.gp DATA ${_fig1_data})
set(FIG1_RESULTS ${_fig1_results})
