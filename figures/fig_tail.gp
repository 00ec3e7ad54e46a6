# SPDX-License-Identifier: GPL-3.0-or-later
# The far tail of the sticky gas's Phi (docs/far-tail.md): ln Phi from the
# biased-chain sampler against the exact Phi (python/exact_ballistic.py, EB8)
# and the Gaussian of the same variance; below, the local exponent
# d ln(-ln(z^2 Phi/A))/d ln z, measured and exact, with 2 and 3 marked.
load styledir.'/style.gp'
load theorydir.'/constants.gp'
load datadir.'/gamma.gp'
set multiplot layout 2, 1 title sprintf('Far tail of Φ, sticky gas, t = %g  (%s)', tail_time, fidelity_note)
set xlabel 'z = V t^{1/3}'
set ylabel 'log_{10} Φ(z)'
set xrange [0:6.5]
set yrange [-60:1]
set key bottom left
set label 1 sprintf("γ = %.3f ± %.3f (chains) ± %.3f (window)\nfit over z ∈ [%.2f, %.2f], b from EB9", \
    tail_gamma, tail_gamma_sigma, tail_gamma_window_systematic, tail_z_lo, tail_z_hi) at graph 0.03, graph 0.45 left font ',10'
l10 = log(10)
# The sampler's points in colour, under a thin exact curve: where they lie on it (nearly everywhere)
# the points show either side of the line (drawn black and thick over black points, they would be hidden).
sampler = 4
exact_line = 'lc rgb "#000000" lw 1'
plot datadir.'/tail.dat' using 1:($2 / l10):($3 / l10) with yerrorbars lt sampler pt 7 ps 0.4 \
         title 'sampler (± jackknife)', \
     theorydir.'/phi_tail.dat' using 1:($2 / l10) with lines @exact_line title 'exact', \
     theorydir.'/phi.dat' using 1:(log($2) / l10) with lines @exact_line notitle, \
     (-x * x / (2 * exact_kappa) - 0.5 * log(2 * pi * exact_kappa)) / l10 with lines lt 8 \
         title sprintf('Gaussian, variance κ = %.4f', exact_kappa)
unset label 1
set ylabel 'local exponent'
set xrange [1:6.5]
set yrange [1:3.5]
set key bottom right
plot datadir.'/tail.dat' using 1:5 with points lt sampler pt 7 ps 0.4 title 'sampler', \
     theorydir.'/phi_tail.dat' using 1:3 with lines @exact_line title 'exact', \
     2 with lines lt 8 dt 2 title 'γ = 2', 3 with lines lt 8 dt 3 title 'γ = 3'
unset multiplot
