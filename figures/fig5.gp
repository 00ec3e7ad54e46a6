# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 5 of Ben-Naim et al. (1999): shock profile of the inelastic gas.
# Top: density (mass per unit length, bins of width L/200); bottom: velocity
# against position, with a line of slope 1/t (Eq. 7: v = (x - q)/t between shocks).
load styledir.'/style.gp'
load datadir.'/shocks.gp'
load datadir.'/burgers.gp'
load theorydir.'/constants.gp'
t = s_shocks0_time
L = s_input_ring_length
N = s_input_particles
width = L / 200.0
bin(x) = width * (floor(x / width) + 0.5)
set multiplot layout 2,1 title sprintf('Fig. 5: shocks at t = %.0f, N = %d, r = %.2f, δ = %g  (%s)', \
    t, N, s_input_restitution, s_input_velocity_threshold, fidelity_note)
set lmargin 12
set xrange [0:L]
set ylabel 'density ρ(x)'
set format x ''
set logscale y
set format y "10^{%L}"
unset key
plot datadir.'/profile.dat' index 0 using (bin($1)):($3 / width) smooth frequency with steps lt 3
unset logscale y
set format y '%g'
set format x '%g'
set xlabel 'position x'
set ylabel 'velocity v(x)'
set key bottom right font ",9"
x0 = L / 2
# Shock counts: the detector's (particles), N t^(-2/3) (the paper), the exact sticky-gas
# cluster count nu N t^(-2/3) (python/exact_ballistic.py, EB6; it counts every cluster,
# singletons included, so it bounds the detector's count from above), and the inviscid
# Burgers shocks from the same initial condition with the detector's rule (drop >= v_rms),
# the like-for-like comparison for the detector.
# A short reference segment of slope 1/t (Eq. 7) above the profile, as long
# as a typical tooth (L / N t^(-2/3)), so it can be compared with the teeth.
tooth = L / s_shocks0_expected_shock_count
stats datadir.'/profile.dat' index 0 using 2 nooutput
span = STATS_max - STATS_min
y_low = STATS_min - 0.28 * span
set yrange [y_low - 0.05 * span : STATS_max + 0.3 * span]
set arrow 1 from 0.62 * L, y_low to 0.62 * L + tooth, y_low + tooth / t nohead lt 4 lw 2.5 front
set label 2 'slope 1/t' at 0.62 * L + tooth, y_low + tooth / t left offset 0.5,0 tc lt 4 font ',9' front
set key bottom left
set label 1 sprintf("%.0f shocks (|Δv| ≥ v_{rms}, one per cluster or bunch); N t^{-2/3} = %.1f; exact clusters ν N t^{-2/3} = %.1f; Burgers (|Δv| ≥ v_{rms}): %d\nsegment slope × t = %.2f ± %.2f (density-corrected %.2f ± %.2f)", \
    s_shocks0_shock_count, s_shocks0_expected_shock_count, exact_nu * s_shocks0_expected_shock_count, \
    burgers_shock_count, s_shocks0_slope_times_t, s_shocks0_slope_times_t_sigma, \
    s_shocks0_density_corrected_slope_times_t, s_shocks0_density_corrected_slope_times_t_sigma) \
    at graph 0.02, graph 0.93 left font ',9'
plot datadir.'/profile.dat' index 0 using 1:2 with points lt 1 pt 7 ps 0.25 title 'particles', \
     datadir.'/burgers.dat' index 0 using 1:2 with lines lt 2 lw 1.2 title 'inviscid Burgers, same initial velocities'
unset multiplot
