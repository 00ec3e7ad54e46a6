# SPDX-License-Identifier: GPL-3.0-or-later
# Early cooling of the pure inelastic gas against Haff's law derived for this
# collision rule (docs/haff-and-collapse.md): T/T0 = 1/(1 + A eps(1-eps) sqrt(T0) t)^2,
# A = 6 sqrt(3)/5, T0 = 1/3. In the variable eps(1-eps) t all eps fall on one
# curve until the gas clusters (t ~ t_stick) and the pure inelastic gas
# collapses (the curves end).
load styledir.'/style.gp'
T0 = 1.0 / 3
A = 6 * sqrt(3) / 5
haff(s) = 1 / (1 + A * sqrt(T0) * s)**2
eps_list = '0.001 0.01 0.05 0.25'
runs = 'eps0.001 eps0.01 eps0.05 eps0.25'
set title sprintf("Early cooling against Haff's law, δ = 0  (%s)", fidelity_note)
set logscale xy
@decades
set xlabel 'ε(1 - ε) t'
set ylabel 'T(t) / T_0'
set xrange [1e-3:1e2]
set yrange [1e-3:1.5]
set key bottom left
plot for [i = 1:4] datadir.'/'.word(runs, i).'.T.dat' \
         using (word(eps_list, i) * (1 - word(eps_list, i)) * $1):($2 / T0) with linespoints lt i pt 7 ps 0.4 \
         title sprintf('ε = %s', word(eps_list, i)), \
     haff(x) with lines lc rgb '#000000' lw 1.5 dt 2 title sprintf("Haff's law, A = 6√3/5 = %.4f", A)
