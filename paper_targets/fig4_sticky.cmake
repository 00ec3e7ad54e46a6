# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 4 with sticky instead of elastic sub-threshold collisions, the paper's
# other mechanism (its Fig. 2 finds the two give the same T(t)). Elastic
# collisions inside a cluster are almost every event of Fig. 4's paper runs
# (about 45 CPU-hours); sticky ones merge the cluster instead, so this
# figure reaches Fig. 4's own N, realizations and times in minutes. The r = 0
# curve is Fig. 4's own run (the sub-threshold rule does not act at r = 0),
# and the seeds are Fig. 4's, so each realization starts where its elastic
# twin does.
shockgas_figure_runs(fig4_sticky)
set(_fig4_sticky_inputs "${fig4_r0_H5}")
foreach(run IN LISTS fig4_sticky_RUNS)
  list(APPEND _fig4_sticky_inputs "${fig4_sticky_${run}_H5}")
endforeach()
shockgas_step(
  OUTPUT "${fig4_sticky_DIR}/phi.dat" "${fig4_sticky_DIR}/scaling.h5" "${fig4_sticky_DIR}/collapse.gp"
  COMMAND shockgas-analyze scaling ${_fig4_sticky_inputs} -o "${fig4_sticky_DIR}/scaling.h5"
          --data "${fig4_sticky_DIR}/phi.dat"
  COMMAND shockgas-dump gnuplot-vars "${fig4_sticky_DIR}/scaling.h5" /collapse --prefix collapse
          --output "${fig4_sticky_DIR}/collapse.gp"
  DEPENDS ${_fig4_sticky_inputs} shockgas-analyze shockgas-dump
  COMMENT "[fig4_sticky] scaling collapse"
  VERBATIM)
# fig4_sticky.gp sets its labels and draws with fig4.gp, so that script is an input too.
shockgas_plot(fig4_sticky SCRIPT fig4_sticky.gp
              DATA "${fig4_sticky_DIR}/phi.dat" "${fig4_sticky_DIR}/collapse.gp"
                   "${PROJECT_SOURCE_DIR}/figures/fig4.gp" ${SHOCKGAS_THEORY_OUTPUTS})
