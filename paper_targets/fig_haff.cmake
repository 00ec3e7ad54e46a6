# SPDX-License-Identifier: GPL-3.0-or-later
# Early-time T(t) of the pure inelastic gas against the derived Haff law.
shockgas_figure_runs(fig_haff)
set(_haff_data)
foreach(run IN LISTS fig_haff_RUNS)
  set(base "${fig_haff_DIR}/${run}")
  shockgas_step(
    OUTPUT "${base}.T.dat"
    COMMAND shockgas-analyze decay "${fig_haff_${run}_H5}" --data-only --data "${base}.T.dat"
    DEPENDS "${fig_haff_${run}_H5}" shockgas-analyze
    COMMENT "[fig_haff] T(t): ${run}"
    VERBATIM)
  list(APPEND _haff_data "${base}.T.dat")
endforeach()
shockgas_plot(fig_haff SCRIPT fig_haff.gp DATA ${_haff_data})
