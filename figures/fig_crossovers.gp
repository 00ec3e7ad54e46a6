# SPDX-License-Identifier: GPL-3.0-or-later
# The crossover times the paper implies (Eq. 3): t_dissip ~ eps^-1, where T
# leaves its initial value (T = T0/2); t_stick ~ eps^-3/2, where the Haff decay
# gives way to the sticky-gas t^(-2/3) (T reaches twice the fitted Haff curve);
# and T(t_stick) ~ eps. Lines: least-squares power laws, exponents +- sigma.
# Dashed: the t_stick the same rule reads on an exact eps^(-3/2) crossover
# (Haff's law with its derived constant joined to the sticky gas's exact
# kappa t^(-2/3)); at these eps Haff's finite-eps terms tilt it to about -1.52.
load styledir.'/style.gp'
load datadir.'/crossovers.gp'
set title sprintf('Crossover times against inelasticity ε = (1 - r)/2  (%s)', fidelity_note)
set logscale xy
@decades
set xlabel 'inelasticity ε'
set ylabel 'time  /  temperature'
# The key below every curve: at the top right it hid two t_stick points at
# paper fidelity, and at the bottom right of [1e-4, 1e4] a T(t_stick) point.
set key bottom right
set xrange [0.004:0.15]
set yrange [1e-5:1e4]
f_dissip(x) = fit_t_dissip_prefactor * x**fit_t_dissip_exponent
f_stick(x) = fit_t_stick_prefactor * x**fit_t_stick_exponent
f_temperature(x) = fit_temperature_at_stick_prefactor * x**fit_temperature_at_stick_exponent
if (!exists('fit_t_stick_exponent')) {
    # The fits over eps are n/a (shockgas-analyze stores a note naming why instead,
    # e.g. an input of one realization has no sigma to weigh by): the points alone.
    set label 1 "fits n/a (why: the note of /scaling_in_eps in crossovers.h5)" noenhanced at graph 0.02, 0.04 font ',8' front
    plot datadir.'/crossovers.dat' using 1:2 with points lt 3 pt 7 title 't_{dissip}', \
         datadir.'/crossovers.dat' using 1:4 with points lt 4 pt 7 title 't_{stick}', \
         datadir.'/crossovers.dat' using 1:10 with linespoints lt 4 dt 2 pt 6 title 'exact ε^{-3/2} crossover, same rule', \
         datadir.'/crossovers.dat' using 1:6 with points lt 5 pt 7 title 'T(t_{stick})'
    unset label 1
} else {
plot datadir.'/crossovers.dat' using 1:2:3 with yerrorbars lt 3 title 't_{dissip}', \
     f_dissip(x) with lines lt 3 title sprintf('t_{dissip} ∝ ε^{%.3f%s}  (-1 at leading order; Haff: 0.345/(ε(1-ε)))', fit_t_dissip_exponent, plus_minus(fit_t_dissip_exponent_sigma, '%.3f')), \
     datadir.'/crossovers.dat' using 1:4:5 with yerrorbars lt 4 title 't_{stick}', \
     f_stick(x) with lines lt 4 title sprintf('t_{stick} ∝ ε^{%.3f%s}  (-3/2 as ε → 0)', fit_t_stick_exponent, plus_minus(fit_t_stick_exponent_sigma, '%.3f')), \
     datadir.'/crossovers.dat' using 1:10 with linespoints lt 4 dt 2 pt 6 title sprintf('exact ε^{-3/2} crossover, same rule: ε^{%.3f} here', fit_t_stick_reference_exponent), \
     datadir.'/crossovers.dat' using 1:6:7 with yerrorbars lt 5 title 'T(t_{stick})', \
     f_temperature(x) with lines lt 5 title sprintf('T(t_{stick}) ∝ ε^{%.3f%s}  (expected +1)', fit_temperature_at_stick_exponent, plus_minus(fit_temperature_at_stick_exponent_sigma, '%.3f'))
}
