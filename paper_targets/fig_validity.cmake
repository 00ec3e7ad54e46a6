# SPDX-License-Identifier: GPL-3.0-or-later
# The validity map of the threshold delta (docs/validity.md): when each
# observable of the delta > 0 gas leaves the sticky gas it stands in for, and
# t* against delta. Its results file holds the map that shockgas-plan and
# shockgas-sim's warning read.
shockgas_figure_runs(fig_validity)
set(_dir "${fig_validity_DIR}")
set(_runs)
foreach(run IN LISTS fig_validity_RUNS)
  list(APPEND _runs "${fig_validity_${run}_H5}")
endforeach()
shockgas_step(
  OUTPUT "${_dir}/validity.h5" "${_dir}/departures.dat" "${_dir}/curves.dat"
  COMMAND shockgas-analyze validity ${_runs} --fidelity ${SHOCKGAS_FIDELITY} -o "${_dir}/validity.h5"
          --data "${_dir}/departures.dat" --curves "${_dir}/curves.dat"
  DEPENDS ${_runs} shockgas-analyze
  COMMENT "[fig_validity] departures from the sticky gas and the fits of t* against delta"
  VERBATIM)
shockgas_plot(fig_validity SCRIPT fig_validity.gp DATA "${_dir}/departures.dat" "${_dir}/curves.dat")
