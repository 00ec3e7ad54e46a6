# SPDX-License-Identifier: GPL-3.0-or-later
# The late decay of inelastic disks (fig_2d.gp) or spheres (fig_3d.gp), which set `dimension`
# and load this (docs/dimensions.md). The paper (closing paragraph) predicts from the inviscid
# Burgers equation T ~ eps^-2 tau^-2 (Haff), then tau^(-d/2) for eps^(-4/(4-d)) << tau << N^(2/d),
# tau = omega0 t in initial collision times; ballistic aggregation gives tau^(-2d/(d+2)).
# (a) T(tau) with the three slopes; (b) the local slope d ln T / d ln tau (1/2-decade chords),
# each run's fitted -theta drawn over its fit window, and the plateau of the local exponent (the
# least steep chord after the overshoot that follows Haff's law) as a dot; (c) T tau^theta (flat in the window);
# (d) the crossover tau_c against eps, fitted and predicted; (e) the velocity kurtosis (3:
# Maxwell); (f) Delta v / v, thermal over coarse-grained flow speed (2D: t^(-1/4) reported by
# Nie, Ben-Naim & Chen 2002); (g) the velocity distribution P(u), u = v_k / sqrt(T), of the
# largest eps at each histogram time; (h) its tail exponent gamma (ln P = a - c |u|^gamma):
# 2 for a Gaussian, 1 for an exponential tail (2D: exponential early, Gaussian late, Nie et al.).
# late.T.dat: 1 t, 2 tau, 3 T, 4 sigma, 5 T t^theta, 6 kurtosis; late.slopes.dat: 1 t, 2 tau,
# 3 slope, 4 smoothed; late.crossovers.dat: 1 eps, 2 tau_c, 3 sigma; late.dv.dat: 1 t, 2 tau,
# 3 dv/v, 4 sigma; late.tails.dat: 1 u, 2 P, 3 sigma (a block per input and histogram time);
# late.tail_fits.dat: 1 t, 2 tau, 3 gamma, 4 sigma; late.fit.gp: ld_late_decay<k>_* and
# ld_crossover_d<d>_* (shockgas-dump).
load styledir.'/style.gp'
# Eight panels: taller than style.gp's page.
if (format eq 'pdf') { set terminal pdfcairo size 6in,9.3in font 'Sans,9' } \
else { if (format eq 'svg') { set terminal svg size 1000,1530 font 'Sans,12' enhanced } \
       else { set terminal pngcairo size 1000,1530 font 'Sans,12' } }
set output outbase.'.'.format
load datadir.'/late.fit.gp'
stats datadir.'/late.T.dat' using 2 nooutput
runs = STATS_blocks
burgers = dimension / 2.0
aggregation = 2.0 * dimension / (dimension + 2.0)
number(k, name) = value(sprintf('ld_late_decay%d_%s', k, name))
plateau_title(k) = (number(k, 'theta_plateau') == number(k, 'theta_plateau')) \
    ? sprintf('; plateau %.2f ± %.2f', number(k, 'theta_plateau'), number(k, 'theta_plateau_sigma')) : ''
run_title(k) = ((number(k, 'theta') == number(k, 'theta')) \
    ? sprintf('ε = %.3g: θ = %.3f ± %.3f ± %.3f', number(k, 'eps'), number(k, 'theta'), \
              number(k, 'theta_sigma'), number(k, 'theta_window_sigma')) \
    : sprintf('ε = %.3g: θ n/a (window empty)', number(k, 'eps'))).plateau_title(k)
crossover = sprintf('ld_crossover_d%d_crossover_', dimension)
# "a ± b", or "n/a" for a number the analysis could not measure (stored as NaN)
pm(a, b) = (a == a) ? sprintf('%.2f ± %.2f', a, b) : 'n/a'

phi = number(0, 'packing_fraction')
set multiplot layout 4,2 title sprintf('%dD, φ = %g, δ = %g, N = %d  (%s)', dimension, phi, \
    number(0, 'velocity_threshold'), number(0, 'particles'), fidelity_note)
set logscale x
set xlabel 'τ = ω_0 t (initial collision times)'
set format x "10^{%L}"
set key bottom left font ',7'

set title '(a) T(τ)' font ',10'
set logscale y
set format y "10^{%L}"
stats datadir.'/late.T.dat' index 0 using 2:3 nooutput
tau_end = STATS_max_x
t_end = STATS_min_y
guide(tau, slope) = 3 * t_end * (tau / tau_end) ** (-slope)
set xrange [0.1:*]
plot for [k = 0:runs - 1] datadir.'/late.T.dat' index k using 2:3 with lines lt k + 1 title sprintf('ε = %.3g', number(k, 'eps')), \
     [tau_end / 100:tau_end] guide(x, 2) lt 8 title 'τ^{-2} (Haff)', \
     [tau_end / 100:tau_end] guide(x, burgers) lt 8 dt 1 lw 1 title sprintf('τ^{-%g} (Burgers)', burgers), \
     [tau_end / 100:tau_end] guide(x, aggregation) lt 6 dt 3 lw 1.5 title sprintf('τ^{-%g} (aggregation)', aggregation)

set title '(b) local slope; fitted -θ (bar), plateau (dot), τ_N (tick)' font ',10'
do for [k = 0:runs - 1] {  # each run's finite-size time, a tick on the lower axis
    set arrow from number(k, 't_finite_size') * number(k, 'collision_frequency'), graph 0 \
        to number(k, 't_finite_size') * number(k, 'collision_frequency'), graph 0.08 nohead lt k + 1 lw 3
}
unset logscale y
set format y '%g'
set ylabel 'd ln T / d ln τ'
set yrange [-2.3:0]
set key top right font ',7'
plot for [k = 0:runs - 1] datadir.'/late.slopes.dat' index k using 2:4 with lines lt k + 1 lw 1 notitle, \
     for [k = 0:runs - 1] [number(k, 'window_start') * number(k, 'collision_frequency'):number(k, 'window_end') * number(k, 'collision_frequency')] \
         -number(k, 'theta') lt k + 1 lw 5 title run_title(k), \
     for [k = 0:runs - 1] '+' using (number(k, 'plateau_time') * number(k, 'collision_frequency')):(-number(k, 'theta_plateau')) \
         every ::0::0 with points lt k + 1 pt 7 ps 1.2 notitle, \
     -2 lt 8 notitle, -burgers lt 8 dt 1 lw 1 title 'Burgers -d/2', -aggregation lt 6 dt 3 lw 1.5 title 'aggregation -2d/(d+2)'

unset arrow
set title '(c) T τ^θ: flat where T ∝ τ^{-θ}' font ',10'
set yrange [*:*]  # before the log scale: [-2.3:0] has no logarithm
set logscale y
set format y "10^{%L}"
set ylabel 'T t^θ'
plot for [k = 0:runs - 1] datadir.'/late.T.dat' index k using 2:5 with lines lt k + 1 title sprintf('ε = %.3g', number(k, 'eps'))

set title '(d) crossover τ_c (Haff meets the late law) against ε' font ',10'
set xlabel 'ε = (1 - r)/2'
set format x '%g'
set xrange [*:*]
set ylabel 'τ_c'
set key top right font ',7'
cross_a = value(crossover.'prefactor')
cross_x = value(crossover.'exponent')
cross_sigma = value(crossover.'exponent_sigma')
predicted = -4.0 / (4 - dimension)
stats datadir.'/late.crossovers.dat' using 2 nooutput  # one column at a time: one point has no regression
tau_mid = sqrt(STATS_min * STATS_max)
stats datadir.'/late.crossovers.dat' using 1 nooutput
eps_mid = sqrt(STATS_min * STATS_max)
tau_mid = (cross_x == cross_x) ? cross_a * eps_mid ** cross_x : tau_mid
set logscale y
set format y "10^{%L}"
set yrange [*:*]
set xrange [STATS_min / 1.3:STATS_max * 1.3]
plot datadir.'/late.crossovers.dat' using 1:2:3 with yerrorbars lt 3 pt 7 title 'measured', \
     (cross_x == cross_x) ? cross_a * x ** cross_x : 1/0 lt 3 title sprintf('fit: ε^{%s}', pm(cross_x, cross_sigma)), \
     tau_mid * (x / eps_mid) ** predicted lt 8 title sprintf('predicted ε^{%g}', predicted)

set title '(e) velocity kurtosis <u^4>/<u^2>^2 (3: Maxwell)' font ',10'
set xlabel 'τ = ω_0 t (initial collision times)'
set format x "10^{%L}"
set xrange [0.1:*]
unset logscale y
set format y '%g'
set yrange [*:*]
set ylabel 'kurtosis'
set key top left font ',7'
plot for [k = 0:runs - 1] datadir.'/late.T.dat' index k using 2:6 with lines lt k + 1 title sprintf('ε = %.3g', number(k, 'eps')), \
     3 lt 8 title 'Maxwell'

set title '(f) Δv/v: thermal over coarse-grained flow speed' font ',10'
set logscale y
set format y '%g'
set ylabel 'Δv / v'
set key bottom left font ',7'
stats datadir.'/late.dv.dat' index 0 using 2:3 nooutput
dv_tau = STATS_max_x
dv_end = STATS_min_y
plot for [k = 0:runs - 1] datadir.'/late.dv.dat' index k using 2:3:4 with yerrorlines lt k + 1 \
         title sprintf('ε = %.3g: exponent %s', number(k, 'eps'), \
                       pm(number(k, 'dv_over_v_exponent'), number(k, 'dv_over_v_exponent_sigma'))), \
     [dv_tau / 1000:dv_tau] dv_end * (x / dv_tau) ** (-0.25) lt 8 title 'τ^{-1/4} (Nie et al. 2D)'

# (g): the last input's histograms, which follow every earlier input's in late.tails.dat.
last = runs - 1
first_block = 0
do for [k = 0:last - 1] { first_block = first_block + number(k, 'histograms') }
histograms = number(last, 'histograms')
set xrange [*:*]  # stats keeps to the x range
tail_taus = ''  # tau of each histogram time, from late.tail_fits.dat's rows
do for [j = 0:histograms - 1] {
    stats datadir.'/late.tail_fits.dat' index last every ::j::j using 2 nooutput
    tail_taus = tail_taus.sprintf(' %.3g', STATS_min)
}
set title sprintf('(g) velocity distribution, ε = %.3g, u = v_k / √T', number(last, 'eps')) font ',10'
set xlabel 'u'
unset logscale x
set format x '%g'
set xrange [-6:6]
set logscale y
set format y "10^{%L}"
stats datadir.'/late.tails.dat' index first_block:first_block + histograms - 1 using ($2 > 0 ? $2 : 1/0) nooutput
set yrange [STATS_min / 3:1]  # down to the emptiest filled bin
set ylabel 'P(u)'
set key bottom center font ',7'
plot for [j = 0:histograms - 1] datadir.'/late.tails.dat' index first_block + j using 1:($2 > 0 ? $2 : 1/0) \
         with lines lt j + 1 title 'τ = '.word(tail_taus, j + 1), \
     exp(-x * x / 2) / sqrt(2 * pi) lt 8 dt 2 title 'Gaussian', \
     exp(-sqrt(2) * abs(x)) / sqrt(2) lt 6 dt 3 title 'exponential'

set title '(h) tail exponent γ of ln P = a - c|u|^γ (2: Gaussian, 1: exponential)' font ',10'
set xlabel 'τ = ω_0 t (initial collision times)'
set logscale x
set format x "10^{%L}"
set xrange [*:*]
unset logscale y
set format y '%g'
set yrange [0:4]
set ylabel 'γ'
set key top left font ',7'
plot for [k = 0:runs - 1] datadir.'/late.tail_fits.dat' index k using 2:3:4 with yerrorlines lt k + 1 \
         title sprintf('ε = %.3g', number(k, 'eps')), \
     2 lt 8 dt 2 title 'Gaussian', 1 lt 6 dt 3 title 'exponential'
unset multiplot
