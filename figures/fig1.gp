# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 1 of Ben-Naim et al. (1999): T(t) for r = 0, 0.5, 0.9, 0.99 (delta = 1e-2),
# the pure inelastic gas (delta = 0) as dots that stop at collapse, the
# paper's reference slope -2/3 and the exact sticky-gas asymptote kappa t^(-2/3).
load styledir.'/style.gp'
load theorydir.'/constants.gp'
runs = 'r0 r0.5 r0.9 r0.99'
ids = 'r0 r0_5 r0_9 r0_99'
names = '"r = 0" "r = 0.5" "r = 0.9" "r = 0.99"'
do for [i = 1:4] { load datadir.'/'.word(runs, i).'.fit.gp' }
exponent(i) = value('fit_'.word(ids, i).'_exponent')
sigma(i) = value('fit_'.word(ids, i).'_exponent_sigma')
window_lo(i) = value('fit_'.word(ids, i).'_t_lo')
window_hi(i) = value('fit_'.word(ids, i).'_t_hi')
curve_title(i) = sprintf('%s:  T ∝ t^{-%.3f%s}  (fit on [%s, %s])', word(names, i), exponent(i), plus_minus(sigma(i), '%.3f'), short_number(window_lo(i)), short_number(window_hi(i)))

set logscale xy
@decades
set xrange [1:*]
set yrange [*:0.5]
set xlabel 'time t  (units of initial spacing / initial velocity)'
set ylabel 'temperature T(t) = ⟨v^2⟩ - ⟨v⟩^2'
set title sprintf('Fig. 1: freely cooling inelastic gas, δ = 10^{-2}  (%s)', fidelity_note)
set key bottom left

plot for [i = 1:4] datadir.'/'.word(runs, i).'.T.dat' using 1:2 with lines lt i title curve_title(i), \
     for [i = 2:4] datadir.'/pure_'.word(runs, i).'.T.dat' using 1:2 with points lt i pt 7 ps 0.5 \
         title sprintf('%s, δ = 0 (stops at inelastic collapse)', word(names, i)), \
     0.6 * x**(-2.0/3) with lines lt 8 lw 1.5 dt 2 title 'slope -2/3', \
     exact_kappa * x**(-2.0/3) with lines lc rgb '#555555' lw 1 dt 3 \
         title sprintf('exact sticky gas: %.4f t^{-2/3}', exact_kappa)
