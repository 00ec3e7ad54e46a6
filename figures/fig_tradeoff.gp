# SPDX-License-Identifier: GPL-3.0-or-later
# The speed/accuracy trade. (a) |<T>/<T_ref> - 1| against t for delta = 1e-2,
# 1e-3, 1e-4 and both sub-threshold mechanisms, the reference being delta =
# 1e-4, elastic, from the same initial conditions (P5: independent of delta up
# to t_valid ~ delta^-3). (b) what each costs: collisions per particle and CPU
# seconds. (c) the sticky gas's decay exponent: statistical error against CPU
# for N = 1e4, 1e5, 1e6 and two ensemble sizes (sigma ~ CPU^(-1/2) expected).
load styledir.'/style.gp'
load datadir.'/reference.gp'
stat_runs = 'stat_N10000_R4 stat_N10000_R16 stat_N100000_R4 stat_N100000_R16 stat_N1000000_R4 stat_N1000000_R16'
stat_ids = 's10000r4 s10000r16 s100000r4 s100000r16 s1000000r4 s1000000r16'
if (fidelity eq 'paper') {
    stat_runs = 'stat_N10000_R10 stat_N10000_R40 stat_N100000_R10 stat_N100000_R40 stat_N1000000_R10 stat_N1000000_R40'
    stat_ids = 's10000r10 s10000r40 s100000r10 s100000r40 s1000000r10 s1000000r40'
}
do for [i = 1:6] { load datadir.'/'.word(stat_runs, i).'.fit.gp' }
set print $stat
do for [i = 1:6] {
    id = word(stat_ids, i)
    print sprintf('%g %g %g %g', value(id.'_input_particles'), value(id.'_input_realizations'), \
                  value(id.'_input_cpu_seconds'), value(id.'_decay_exponent_sigma'))
}
unset print

# The compared runs, in the order of the JSON file without the reference.
if (fidelity eq 'paper') {
    names = '"δ = 10^{-3}, elastic" "δ = 10^{-2}, elastic" "δ = 10^{-4}, sticky" "δ = 10^{-3}, sticky" "δ = 10^{-2}, sticky"'
    reference_name = 'δ = 10^{-4}, elastic'
    compared = 5
} else {
    names = '"δ = 10^{-3}, elastic" "δ = 10^{-2}, elastic" "δ = 10^{-3}, sticky" "δ = 10^{-2}, sticky"'
    reference_name = 'δ = 10^{-4}, sticky'
    compared = 4
}
set multiplot layout 2,2 title sprintf('Speed/accuracy trade, r = 0.9, N = %d, %d realizations  (%s)', \
    reference_particles, reference_realizations, fidelity_note)
set logscale xy
@decades
set xlabel 'time t'
set ylabel '|⟨T⟩ / ⟨T_{ref}⟩ - 1|'
set title sprintf('(a) deviation from %s', reference_name) font ',10'
set key top left font ',8'
set yrange [1e-5:1]
plot for [b = 0:1] datadir.'/deviation.dat' index b using 1:(abs($2)) with lines lt (b + 2) title word(names, b + 1), \
     for [b = 2:compared - 1] datadir.'/deviation.dat' index b using 1:(abs($2)) with lines lt (b + 2) dt 2 title word(names, b + 1)

set title '(b) cost' font ',10'
set xlabel 'velocity threshold δ'
set ylabel 'collisions per particle / CPU seconds'
set yrange [*:*]
set xrange [5e-5:2e-2]
set key bottom left font ',8'
plot datadir.'/tradeoff.dat' using 1:($2 == 0 ? $3 : NaN) with linespoints lt 2 pt 7 title 'collisions/particle, elastic', \
     datadir.'/tradeoff.dat' using 1:($2 == 1 ? $3 : NaN) with linespoints lt 4 pt 5 title 'collisions/particle, sticky', \
     '+' using (1e-4):(reference_total_collisions / reference_particles / reference_realizations) every ::0::0 \
         with points lt 2 pt 6 ps 1.5 title sprintf('reference (%s)', reference_name), \
     datadir.'/tradeoff.dat' using 1:($2 == 0 ? $4 : NaN) with linespoints lt 2 pt 7 dt 3 title 'CPU s, elastic', \
     datadir.'/tradeoff.dat' using 1:($2 == 1 ? $4 : NaN) with linespoints lt 4 pt 5 dt 3 title 'CPU s, sticky'

set title '(c) sticky gas: error of the decay exponent' font ',10'
set xlabel 'CPU seconds'
set ylabel 'σ(α)'
set xrange [*:*]
set key top right font ',8'
plot $stat using 3:($1 == 10000 ? $4 : NaN) with points lt 3 pt 7 ps 1.2 title 'N = 10^4', \
     $stat using 3:($1 == 100000 ? $4 : NaN) with points lt 5 pt 5 ps 1.2 title 'N = 10^5', \
     $stat using 3:($1 == 1000000 ? $4 : NaN) with points lt 6 pt 9 ps 1.2 title 'N = 10^6', \
     $stat using 3:4:(sprintf('R = %d', $2)) with labels offset 0,1 font ',7' notitle
unset multiplot
