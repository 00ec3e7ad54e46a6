# SPDX-License-Identifier: GPL-3.0-or-later
# Clusters of the inelastic disks of fig_2d or spheres of fig_3d (docs/dimensions.md). In 2D: (a-c)
# the density field of realization 0 of the first run (the smallest eps) at three snapshots; then,
# in 2D and 3D, the largest cluster and the mass-weighted mean cluster mass against t, with the
# paper's critical size scale N_c ~ eps^(-2d/(4-d)) (horizontal, in particles; the prefactor is not
# predicted), and the cluster mass distribution at the last snapshot. A cluster: field cells at
# density >= 2 x the mean joined through faces (shockgas-analyze clusters).
# clusters.dat: 1 t, 2 clusters, 3 sigma, 4 mean mass, 5 sigma, 6 largest, 7 sigma, 8 fraction,
# 9 sigma, a block per run; clusters.masses.dat: 1 lo, 2 hi, 3 centre, 4 clusters per realization,
# 5 per unit mass, a block per run and snapshot; clusters.maps.dat (2D): 1 x, 2 y, 3 density, a block
# per snapshot; clusters.fit.gp: cl_clusters<k>_* (shockgas-dump).
load styledir.'/style.gp'
load datadir.'/clusters.fit.gp'
stats datadir.'/clusters.dat' using 1 nooutput
runs = STATS_blocks
stats datadir.'/clusters.dat' index 0 using 1 nooutput
snapshots = STATS_records
number(k, name) = value(sprintf('cl_clusters%d_%s', k, name))
eps(k) = (1 - number(k, 'restitution')) / 2
d = int(number(0, 'dimension'))
# N_c's exponent -2d/(4-d), for the legend: -2 in 2D, -6 in 3D.
critical_exponent = -2 * d / (4 - d)
set multiplot title sprintf('%dD clusters, φ = %g, N = %d, %d^%d field cells, threshold 2  (%s)', d, \
    number(0, 'packing_fraction'), number(0, 'particles'), number(0, 'field_cells'), d, fidelity_note)
# 2D: top row three maps, bottom row two plots (panels d, e). 3D: the two plots (a, b) alone.
if (d == 2) {
    set size ratio -1
    unset key
    set palette defined (0 'white', 1 '#56B4E9', 3 '#0072B2', 8 '#000000')
    set cbrange [0:8]
    set cbtics font ',7'
    set format x '%g'
    set format y '%g'
    set xtics font ',7'
    set ytics font ',7'
    do for [m = 1:3] {
        s = snapshots - 4 + m
        set origin (m - 1) / 3.0, 0.5
        set size 1 / 3.0, 0.45
        set autoscale xy
        stats datadir.'/clusters.dat' index 0 every ::s::s using 1 nooutput
        set title sprintf('(%s) ε = %.3g, t = %g', word('a b c', m), eps(0), STATS_min) font ',10'
        stats datadir.'/clusters.maps.dat' index s using 1 nooutput
        set xrange [0:STATS_max + STATS_min]
        set yrange [0:STATS_max + STATS_min]
        plot datadir.'/clusters.maps.dat' index s using 1:2:3 with image
    }
    unset colorbox
}
plots_height = d == 2 ? 0.5 : 0.95
letters = d == 2 ? 'd e' : 'a b'
set size noratio
set xtics font ',10'
set ytics font ',10'
set origin 0, 0
set size 0.5, plots_height
set title sprintf('(%s) largest (points) and mean (lines) cluster mass', word(letters, 1)) font ',10'
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [*:*]
set yrange [*:*]
set xlabel 't'
set ylabel 'particles'
set key top left font ',7'
plot for [k = 0:runs - 1] datadir.'/clusters.dat' index k using 1:6:7 with yerrorbars lt k + 1 pt 7 \
         title sprintf('ε = %.3g', eps(k)), \
     for [k = 0:runs - 1] datadir.'/clusters.dat' index k using 1:4 with lines lt k + 1 notitle, \
     for [k = 0:runs - 1] number(k, 'critical_size_scale') lt k + 1 dt 2 lw 1 notitle
set origin 0.5, 0
set size 0.5, plots_height
set title sprintf('(%s) cluster masses at the last snapshot', word(letters, 2)) font ',10'
set xlabel 'cluster mass m (particles)'
set ylabel 'clusters per realization per unit mass'
set key top right font ',7'
plot for [k = 0:runs - 1] datadir.'/clusters.masses.dat' index k * snapshots + snapshots - 1 \
         using 3:($5 > 0 ? $5 : 1/0) with linespoints lt k + 1 title sprintf('ε = %.3g (ε^{%d} = %.0f)', eps(k), critical_exponent, eps(k)**critical_exponent)
unset multiplot
