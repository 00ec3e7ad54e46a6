# SPDX-License-Identifier: GPL-3.0-or-later
# The validity map of the threshold delta (docs/validity.md). (a)-(c) t*, the
# time from which each observable stays outside 3 paired-jackknife sigma of the
# sticky gas (T also: 1 % and 5 %), against delta, with the fits t* = A delta^-mu
# and the delta^-1 and delta^-3 lines; open triangles: still inside at the
# run's last time (t* beyond it). (d) one structural observable, the cluster
# density n t^(2/3)/nu, as its difference from the sticky gas for each delta
# (r = 0.9, elastic below delta), n / n_sticky - 1: never near 0 at r = 0.9.
#
# departures.dat columns: 1 r, 2 sticky (0/1), 3 N, 4 observable (0 T,
# 1 kurtosis, 2 cluster density, 3 small-gap fraction, 4 structure function,
# 5 fragmentation rate), 5 criterion (0 3 sigma, 1 1 %, 2 5 %), 6 delta, 7 t*,
# 8 sigma, 9 status (0 departed, 1 still inside at t_end, 2 never joined),
# 10 mu, 11 mu sigma, 12 ln A.
# curves.dat: one block per compared run (the JSON's order without the
# references: r = 0.5 elastic, r = 0.5 sticky, r = 0.9 elastic, r = 0.9
# sticky, five deltas each from 1e-1 down, then the N check) and observable.
load styledir.'/style.gp'
d = datadir.'/departures.dat'
main_n = (fidelity eq 'paper') ? 100000 : 10000
names = '"T (3σ)" "kurtosis" "cluster density" "small-gap fraction" "S(k), k t^{2/3} = 100" "fragmentation rate"'
# The observable's points of one panel: r, mechanism, criterion and status.
sel(r, sticky, o, c, s) = (abs($1 - r) < 1e-9 && $2 == sticky && $3 == main_n && $4 == o && $5 == c && $9 == s) ? $7 : NaN
fitline(r, sticky, o, c) = (abs($1 - r) < 1e-9 && $2 == sticky && $3 == main_n && $4 == o && $5 == c && $9 == 0 && $10 == $10) \
                           ? exp($12) * $6**(-$10) : NaN

set multiplot layout 2,2 title sprintf('Validity map of δ: when the gas leaves the sticky gas, N = %d  (%s)', \
    main_n, fidelity_note)
set logscale xy
@decades
set xrange [6e-4:0.16]
set yrange [0.5:1e10]
set xlabel 'velocity threshold δ'
set ylabel 'departure time t*'
set key top right font ',7' spacing 1.0
panel(r, sticky, label) = sprintf('(%s) r = %g, %s below δ', label, r, sticky ? 'sticky' : 'elastic')
do for [p = 1:3] {
    r = (p == 2) ? 0.5 : 0.9
    sticky = (p == 3) ? 1 : 0
    set title panel(r, sticky, word('a b c', p)) font ',10'
    set label 1 '△: still inside at the last time; not drawn: never joined' \
        at graph 0.02, graph 0.04 font ',7'
    plot for [o = 0:5] d using 6:(sel(r, sticky, o, 0, 0)):8 with yerrorbars lt (o + 1) pt 7 title word(names, o + 1), \
         for [o = 0:5] d using 6:(fitline(r, sticky, o, 0)) with lines lt (o + 1) dt 2 notitle, \
         for [o = 0:5] d using 6:(sel(r, sticky, o, 0, 1)) with points lt (o + 1) pt 8 ps 1.2 notitle, \
         d using 6:(sel(r, sticky, 0, 1, 0)) with points lt 1 pt 4 ps 1.1 title 'T (1 %)', \
         d using 6:(sel(r, sticky, 0, 2, 0)) with points lt 1 pt 12 ps 1.1 title 'T (5 %)', \
         [6e-4:0.16] 10 * (x / 0.1)**(-1) with lines lt 8 lw 1 title 'δ^{-1}', \
         [6e-4:0.16] 10 * (x / 0.1)**(-3) with lines lt 8 lw 1 dt 3 title 'δ^{-3}'
}

unset label 1
set title '(d) cluster density against the sticky gas, r = 0.9, elastic' font ',10'
set xlabel 'time t'
set ylabel 'n / n_{sticky} - 1'
unset logscale y
set format y '%g'
set xrange [1:*]
set yrange [*:*]
set key top right font ',8'
deltas = '"δ = 10^{-1}" "δ = 10^{-1.5}" "δ = 10^{-2}" "δ = 10^{-2.5}" "δ = 10^{-3}"'
plot for [i = 0:4] datadir.'/curves.dat' index ((10 + i) * 6 + 2) using 1:2:3 with yerrorlines lt (i + 2) pt 7 ps 0.5 \
         title word(deltas, i + 1), \
     0 with lines lt 1 lw 1 title 'sticky gas'
unset multiplot
