# SPDX-License-Identifier: GPL-3.0-or-later
# The far tail of Phi (docs/far-tail.md): the sticky gas's Phi(z) from
# the biased-chain sampler down to ~1e-55 against the exact curve, with gamma
# fitted and the local exponent. The sampler's options per fidelity are here
# (it is not a shockgas-sim run, so it has no JSON run list): quick ~25 s CPU
# at t = 100, paper ~34 min CPU at t = 1000. The paper tier's chains are long
# because shorter ones fall below the exact Phi deep in the tail (a factor 2-3
# at 1e-34 with 4 x 400 000 steps per bias) and these do not (docs/far-tail.md;
# the runs: docs/measurements.md, "Longer chains").
if(SHOCKGAS_FIDELITY STREQUAL "paper")
  set(_tail_options -t 1000 --half-window 900 --focus 800 --block-max 400 --steps-per-bias 1600000
                    --burn-in 100000 --chains 4 --seed 9)
else()
  set(_tail_options -t 100 --half-window 300 --focus 250 --block-max 150 --steps-per-bias 30000 --burn-in 6000
                    --chains 4 --seed 2026)
endif()
set(fig_tail_DIR "${CMAKE_CURRENT_BINARY_DIR}/${SHOCKGAS_FIDELITY}/fig_tail")
file(MAKE_DIRECTORY "${fig_tail_DIR}")
shockgas_step(
  OUTPUT "${fig_tail_DIR}/tail.h5"
  COMMAND shockgas-tail ${_tail_options} --z-reach 6 --z-step 0.25 -o "${fig_tail_DIR}/tail.h5"
  # The sampler's own source stamp (pipeline.cmake), not the binary, which relinks at
  # every commit: it reruns only when sim/tail, or the model or I/O it uses, changes.
  DEPENDS ${SHOCKGAS_TAIL_STAMP}
  COMMENT "[fig_tail] far-tail sampler"
  VERBATIM)
shockgas_step(
  OUTPUT "${fig_tail_DIR}/tail.dat" "${fig_tail_DIR}/gamma.h5" "${fig_tail_DIR}/gamma.gp"
  COMMAND shockgas-analyze far-tail "${fig_tail_DIR}/tail.h5" -o "${fig_tail_DIR}/gamma.h5"
          --data "${fig_tail_DIR}/tail.dat"
  COMMAND shockgas-dump gnuplot-vars "${fig_tail_DIR}/gamma.h5" /far_tail --prefix tail
          --output "${fig_tail_DIR}/gamma.gp"
  DEPENDS "${fig_tail_DIR}/tail.h5" shockgas-analyze shockgas-dump
  COMMENT "[fig_tail] gamma"
  VERBATIM)
shockgas_plot(fig_tail SCRIPT fig_tail.gp DATA "${fig_tail_DIR}/tail.dat" "${fig_tail_DIR}/gamma.gp"
              ${SHOCKGAS_THEORY_OUTPUTS})
add_dependencies(fig_tail shockgas_tail_stamp)
