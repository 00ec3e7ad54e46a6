# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 5: density and velocity profile at the snapshot time; shocks counted and
# the slopes of the segments between them fitted (Eq. 7: slope 1/t). The count
# is shockgas-analyze's default rule, the one shockgas-burgers compares with
# Burgers, so the build log's two counts of this snapshot are one; the segments
# are fitted to cells of 20 particles, which the elastic bunches' jitter would bend.
shockgas_figure_runs(fig5)
shockgas_step(
  OUTPUT "${fig5_DIR}/profile.dat" "${fig5_DIR}/shocks.h5" "${fig5_DIR}/shocks.gp"
  COMMAND shockgas-analyze shocks "${fig5_profile_H5}" -o "${fig5_DIR}/shocks.h5" --data "${fig5_DIR}/profile.dat"
          --coarse-grain 20
  COMMAND shockgas-dump gnuplot-vars "${fig5_DIR}/shocks.h5" / --recursive --prefix s --output "${fig5_DIR}/shocks.gp"
  DEPENDS "${fig5_profile_H5}" shockgas-analyze shockgas-dump
  COMMENT "[fig5] shocks"
  VERBATIM)
# Inviscid Burgers from the same initial condition (the run's
# seed, N, L), at the snapshot time: the continuum limit the shocks are compared with (docs/continuum.md).
shockgas_step(
  OUTPUT "${fig5_DIR}/burgers.dat" "${fig5_DIR}/burgers.gp"
  COMMAND shockgas-burgers --run "${fig5_profile_H5}" --cells-per-particle 4
          --output "${fig5_DIR}/burgers.dat" --summary "${fig5_DIR}/burgers.gp"
  DEPENDS "${fig5_profile_H5}" shockgas-burgers
  COMMENT "[fig5] Burgers profile from the run's initial condition"
  VERBATIM)
shockgas_plot(fig5 SCRIPT fig5.gp DATA "${fig5_DIR}/profile.dat" "${fig5_DIR}/shocks.gp"
              "${fig5_DIR}/burgers.dat" "${fig5_DIR}/burgers.gp" ${SHOCKGAS_THEORY_OUTPUTS})
add_dependencies(fig5 shockgas-burgers)
