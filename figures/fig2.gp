# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 2 of Ben-Naim et al. (1999): role of the velocity threshold delta and of
# the sub-threshold mechanism, r = 0.9. Top: T(t); bottom: each T(t) divided by
# the delta = 1e-3, elastic curve (same initial conditions: same seed).
load styledir.'/style.gp'
runs = 'd1e-2_elastic d1e-3_elastic d1e-2_sticky d1e-3_sticky'
ids = 'd1e_2_elastic d1e_3_elastic d1e_2_sticky d1e_3_sticky'
names = '"δ = 10^{-2}, elastic" "δ = 10^{-3}, elastic" "δ = 10^{-2}, sticky" "δ = 10^{-3}, sticky"'
do for [i = 1:4] { load datadir.'/'.word(runs, i).'.fit.gp' }
exponent(i) = value('fit_'.word(ids, i).'_exponent')
sigma(i) = value('fit_'.word(ids, i).'_exponent_sigma')
file(i) = datadir.'/'.word(runs, i).'.T.dat'
reference = file(2)

set multiplot layout 2,1 title sprintf('Fig. 2: threshold and sub-threshold mechanism, r = 0.9  (%s)', fidelity_note)
set logscale xy
@decades
set lmargin 12
set ylabel 'temperature T(t)'
set xlabel ''
set format x ''
set key bottom left
set size 1, 0.62
set origin 0, 0.36
plot for [i = 1:2] file(i) using 1:2 with lines lt i \
         title sprintf('%s:  T ∝ t^{-%.3f%s}', word(names, i), exponent(i), plus_minus(sigma(i), '%.3f')), \
     for [i = 3:4] file(i) using 1:2 with lines lt i dt 2 \
         title sprintf('%s:  T ∝ t^{-%.3f%s}', word(names, i), exponent(i), plus_minus(sigma(i), '%.3f')), \
     0.6 * x**(-2.0/3) with lines lt 8 title 'slope -2/3'
unset logscale y
set format y '%.2f'
set format x "10^{%L}"
set ylabel 'T / T_{δ=10^{-3}, elastic}'
set xlabel 'time t'
set size 1, 0.36
set origin 0, 0
set yrange [0.8:1.2]
set key off
plot for [i = 1:2] '< paste '.file(i).' '.reference using 1:($2/$5) with lines lt i, \
     for [i = 3:4] '< paste '.file(i).' '.reference using 1:($2/$5) with lines lt i dt 2, \
     1 with lines lt 8
unset multiplot
