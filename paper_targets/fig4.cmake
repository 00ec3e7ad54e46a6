# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 4: the mass-weighted velocity distributions of r = 0, 0.5, 0.9 at three
# times, rescaled by t^(1/3); scaling exponent, kurtosis and tail fitted.
shockgas_figure_runs(fig4)
set(_fig4_inputs)
foreach(run IN LISTS fig4_RUNS)
  list(APPEND _fig4_inputs "${fig4_${run}_H5}")
endforeach()
shockgas_step(
  OUTPUT "${fig4_DIR}/phi.dat" "${fig4_DIR}/scaling.h5" "${fig4_DIR}/collapse.gp"
  COMMAND shockgas-analyze scaling ${_fig4_inputs} -o "${fig4_DIR}/scaling.h5" --data "${fig4_DIR}/phi.dat"
  COMMAND shockgas-dump gnuplot-vars "${fig4_DIR}/scaling.h5" /collapse --prefix collapse
          --output "${fig4_DIR}/collapse.gp"
  DEPENDS ${_fig4_inputs} shockgas-analyze shockgas-dump
  COMMENT "[fig4] scaling collapse"
  VERBATIM)
shockgas_plot(fig4 SCRIPT fig4.gp DATA "${fig4_DIR}/phi.dat" "${fig4_DIR}/collapse.gp" ${SHOCKGAS_THEORY_OUTPUTS})
