# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 3: world lines of 500 particles (snapshots every unit of time).
shockgas_figure_runs(fig3)
shockgas_step(
  OUTPUT "${fig3_DIR}/worldlines.dat"
  COMMAND shockgas-dump snapshots "${fig3_worldlines_H5}" --output "${fig3_DIR}/worldlines.dat"
  DEPENDS "${fig3_worldlines_H5}" shockgas-dump
  COMMENT "[fig3] world lines"
  VERBATIM)
shockgas_plot(fig3 SCRIPT fig3.gp DATA "${fig3_DIR}/worldlines.dat")
