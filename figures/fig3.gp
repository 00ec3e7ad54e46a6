# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 3 of Ben-Naim et al. (1999): space-time evolution of 500 particles,
# r = 0.9, delta = 1e-2, up to t = 600. Each dot is one particle at one
# snapshot (every unit of time); the particles' order never changes, so the
# dots trace world lines. Clusters appear as dense bundles that merge.
load styledir.'/style.gp'
set title sprintf('Fig. 3: world lines of N = 500 particles, r = 0.9, δ = 10^{-2}  (%s)', fidelity_note)
set xlabel 'position x  (ring of length L = 500)'
set ylabel 'time t'
set xrange [0:500]
set yrange [0:600]
set mxtics 5
set mytics 5
unset key
set grid front
plot datadir.'/worldlines.dat' using 2:1 with dots lc rgb '#000000'
