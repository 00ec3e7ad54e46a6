# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 2: role of the velocity threshold and of the sub-threshold mechanism
# (r = 0.9). Every curve gets its decay exponent; the lower panel shows each
# T(t) relative to delta = 1e-3, elastic (the most accurate setting).
shockgas_figure_runs(fig2)
set(_fig2_data)
foreach(run IN LISTS fig2_RUNS)
  set(base "${fig2_DIR}/${run}")
  string(MAKE_C_IDENTIFIER "${run}" id)
  shockgas_step(
    OUTPUT "${base}.T.dat" "${base}.decay.h5" "${base}.fit.gp"
    COMMAND shockgas-analyze decay "${fig2_${run}_H5}" -o "${base}.decay.h5" --data "${base}.T.dat"
    COMMAND shockgas-dump gnuplot-vars "${base}.decay.h5" /decay --prefix "fit_${id}" --output "${base}.fit.gp"
    DEPENDS "${fig2_${run}_H5}" shockgas-analyze shockgas-dump
    COMMENT "[fig2] decay exponent: ${run}"
    VERBATIM)
  list(APPEND _fig2_data "${base}.T.dat" "${base}.fit.gp")
endforeach()
shockgas_plot(fig2 SCRIPT fig2.gp DATA ${_fig2_data})
