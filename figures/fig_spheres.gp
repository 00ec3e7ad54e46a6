# SPDX-License-Identifier: GPL-3.0-or-later
# Inelastic hard disks and spheres (docs/spheres.md): (a) T(t) over Haff's law
# T_H = 1/(1 + t/t0)^2, t0 = 2d / ((1 - r^2) omega_Enskog), against t/t0: on 1
# within 2 % until clustering sets in; (b) the clustering index (variance over
# mean of the particle count per field cell: 1 for independent particles) as the
# gas clusters; (c) the disks of the 2D r = 0.9 run at its last snapshot.
# cooling.T.dat columns: 1 t, 2 t/t0, 3 T, 4 sigma, 5 T_H, 6 T/T_H, 7 sigma; a
# block per run in the JSON's order (2D r = 0.9, 2D r = 0.99, 3D r = 0.9, 3D r = 0.99).
load styledir.'/style.gp'
names = '"2D, r = 0.9" "2D, r = 0.99" "3D, r = 0.9" "3D, r = 0.99"'
set multiplot layout 2,2 title sprintf('Inelastic disks and spheres, φ = 0.1, δ = 10^{-2}  (%s)', fidelity_note)
set logscale x
set format x "10^{%L}"
set xtics 100
set xlabel 't / t_0'
set xrange [1e-3:2e3]
set key bottom left font ',8'
set title '(a) T(t) and Haff''s law (dashed)' font ',10'
set ylabel 'T(t)'
set logscale y
set format y "10^{%L}"
set yrange [1e-7:2]
plot for [i = 0:3] datadir.'/cooling.T.dat' index i using 2:3 with lines lt i + 1 title word(names, i + 1), \
     for [i = 0:0] datadir.'/cooling.T.dat' index i using 2:5 with lines lt 8 title 'Haff, t_0 from Enskog'
set title '(b) T / Haff' font ',10'
set ylabel 'T(t) / T_{Haff}(t)'
set key top left font ',8'
set yrange [0.95:2]
set format y '%g'
set ytics (0.95, 1, 1.05, 1.1, 1.2, 1.5, 2)
plot for [i = 0:3] datadir.'/cooling.T.dat' index i using 2:6:7 with yerrorlines lt i + 1 pt 7 ps 0.3 \
         title word(names, i + 1), \
     1.02 with lines lt 8 notitle, 0.98 with lines lt 8 title '±2 %'
set title '(c) clustering index' font ',10'
set ylabel 'count variance / mean, per field cell'
set yrange [0.5:*]
set ytics auto
set format y '%g'
set xrange [0.5:2e3]
plot for [i = 0:3] datadir.'/cooling.clustering.dat' index i using 2:3:4 with yerrorlines lt i + 1 pt 7 ps 0.5 \
         title word(names, i + 1), \
     1 with lines lt 8 title 'independent particles'
set title '(d) 2D, r = 0.9: the disks at the last snapshot' font ',10'
unset logscale
set format x '%g'
set format y '%g'
set xtics auto
set ytics auto
set xlabel 'x'
set ylabel 'y'
set size ratio -1
set autoscale
set xrange [0:*]
set yrange [0:*]
unset key
plot datadir.'/cooling.picture.dat' using 1:2 with dots lc rgb '#0072B2'
unset multiplot
