# SPDX-License-Identifier: GPL-3.0-or-later
# Inelastic collapse of the pure inelastic gas (delta = 0) against eps and N
# (docs/haff-and-collapse.md, "Collapse against eps and N").
# (a) t_collapse eps^(3/2) and (b) cluster mass x eps against eps, at N = K/eps
#     (a fixed number of regions of size 1/eps), with the fitted forms: a free
#     power eps^x; the paper's eps^-3/2 (eps^-1) with a free log correction
#     (ln 1/eps)^y; the paper's law alone; McNamara & Young's minimal cluster
#     ln(1/2eps)/(2eps) (and t ~ its 3/2 power). Each legend gives dAIC.
# (c) mean first-collapse time against N at one eps (bars: SE; open: the
#     spread of single realizations), with a power law and, where N/m >= 50,
#     the Gumbel law of a minimum over many regions (mean a - tau ln N, spread
#     pi tau / sqrt 6 at every N);
# (d) the cumulative collapse hazard per particle H(t)/N for each N: one curve
#     if the first collapse is the earliest of independent regions (log y,
#     linear t: straight where the hazard rises exponentially).
load styledir.'/style.gp'
load datadir.'/time_forms.gp'
load datadir.'/mass_forms.gp'
load datadir.'/vs_N.gp'
# Before any range is set (stats honours them): the eps of the N series, and
# its N values in file order, which is the order of the blocks of hazard.dat.
stats datadir.'/vs_N.dat' using 1 nooutput
eps_N = STATS_min
particles = ''
stats datadir.'/vs_N.dat' using (particles = particles.sprintf(' %d', $2), $2) nooutput
blocks = words(particles)
set multiplot layout 2,2 title sprintf('Inelastic collapse, δ = 0  (%s)', fidelity_note)
set key font ',8' spacing 1.0

set logscale x
set logscale y
set format x '10^{%L}'
set xlabel 'inelasticity ε'
set xrange [0.4:3e-4]
set yrange [0.5:30]
set ylabel 't_{collapse} ε^{3/2}'
set key top left
tp(x) = time_power_prefactor * x**(time_power_exponent + 1.5)
tl(x) = time_log_corrected_prefactor * log(1 / x)**time_log_corrected_exponent
tq(x) = time_paper_prefactor
tm(x) = time_mcnamara_young_prefactor * (log(1 / (2 * x)) / 2)**1.5
if (!exists('time_power_exponent')) {
    # The fits are n/a (shockgas-analyze stores a note naming why instead, e.g.
    # an input of one realization has no sigma to weigh by): draw the points
    # alone, without error bars, and say where the reason is.
    set label 1 "forms n/a (why: the note of /time_forms in vs_eps.h5)" noenhanced at graph 0.02, 0.06 font ',7' front
    plot datadir.'/vs_eps.dat' using 1:($3 * $1**1.5) with points lt 1 pt 7 title 'N = K/ε (forms n/a)'
    unset label 1
} else {
plot datadir.'/vs_eps.dat' using 1:($3 * $1**1.5):($4 * $1**1.5) with yerrorbars lt 1 title 'N = K/ε', \
     tp(x) lt 2 title sprintf('ε^{%.3f%s}  ΔAIC %.0f', time_power_exponent, plus_minus(time_power_exponent_sigma_scaled, '%.3f'), time_power_delta_aic), \
     tl(x) lt 3 title sprintf('ε^{-3/2}(ln 1/ε)^{%.2f%s}  ΔAIC %.0f', time_log_corrected_exponent, plus_minus(time_log_corrected_exponent_sigma_scaled, '%.2f'), time_log_corrected_delta_aic), \
     tq(x) lt 4 title sprintf('ε^{-3/2}  ΔAIC %.0f', time_paper_delta_aic), \
     tm(x) lt 5 title sprintf('[ln(1/2ε)/2ε]^{3/2}  ΔAIC %.0f', time_mcnamara_young_delta_aic)
}

set ylabel 'cluster mass × ε'
set yrange [1.5:5]
set ytics (1.5, 2, 2.5, 3, 4, 5)
set format y '%g'
set key top left
mp(x) = mass_power_prefactor * x**(mass_power_exponent + 1)
ml(x) = mass_log_corrected_prefactor * log(1 / x)**mass_log_corrected_exponent
mq(x) = mass_paper_prefactor
mm(x) = mass_mcnamara_young_prefactor * log(1 / (2 * x)) / 2
if (!exists('mass_power_exponent')) {
    set label 1 "forms n/a (why: the note of /mass_forms in vs_eps.h5)" noenhanced at graph 0.02, 0.06 font ',7' front
    plot datadir.'/vs_eps.dat' using 1:($5 * $1) with points lt 1 pt 7 title 'N = K/ε (forms n/a)'
    unset label 1
} else {
plot datadir.'/vs_eps.dat' using 1:($5 * $1):($6 * $1) with yerrorbars lt 1 title 'N = K/ε', \
     mp(x) lt 2 title sprintf('ε^{%.3f%s}  ΔAIC %.0f', mass_power_exponent, plus_minus(mass_power_exponent_sigma_scaled, '%.3f'), mass_power_delta_aic), \
     ml(x) lt 3 title sprintf('ε^{-1}(ln 1/ε)^{%.3f%s}  ΔAIC %.0f', mass_log_corrected_exponent, plus_minus(mass_log_corrected_exponent_sigma_scaled, '%.3f'), mass_log_corrected_delta_aic), \
     mq(x) lt 4 title sprintf('ε^{-1}  ΔAIC %.0f', mass_paper_delta_aic), \
     mm(x) lt 5 title sprintf('ln(1/2ε)/2ε  ΔAIC %.0f', mass_mcnamara_young_delta_aic)
}

set xrange [*:*]
set yrange [*:*]
set ytics auto
set format y '10^{%L}'
set xlabel 'particles N'
set ylabel 't_{collapse}'
set key top right
set offsets 0, 0, graph 0.6, 0   # headroom for the key above the points
set title sprintf('first collapse at ε = %g', eps_N) font ',9'
tn(x) = fit_mean_time_prefactor * x**fit_mean_time_exponent
tg(x) = fit_gumbel_intercept - fit_gumbel_tau * log(x)
if (!exists('fit_mean_time_exponent')) {
    set label 1 "fits n/a (why: the note of /first_collapse in vs_N.h5)" noenhanced at graph 0.02, 0.06 font ',7' front
    plot datadir.'/vs_N.dat' using 2:3 with points lt 1 pt 7 title '⟨t_{collapse}⟩ (fits n/a)'
    unset label 1
} else {
if (!exists('fit_gumbel_tau')) {
    # Too few runs with N/m >= gumbel_min_regions: the Gumbel law is n/a, the rest stands.
    set label 1 sprintf('Gumbel fit n/a: %s', fit_gumbel_note) noenhanced at graph 0.02, 0.06 font ',7' front
    plot datadir.'/vs_N.dat' using 2:3:4 with yerrorbars lt 1 title '⟨t_{collapse}⟩ ± SE', \
         datadir.'/vs_N.dat' using 2:9 with points lt 6 pt 6 title 'spread (s.d.)', \
         tn(x) lt 2 title sprintf('N^{%.3f%s}  (χ^2/dof %s)', fit_mean_time_exponent, plus_minus(fit_mean_time_exponent_sigma, '%.3f'), \
             number_or_na(fit_mean_time_chi2_per_dof, '%.1f'))
    unset label 1
} else {
plot datadir.'/vs_N.dat' using 2:3:4 with yerrorbars lt 1 title '⟨t_{collapse}⟩ ± SE', \
     datadir.'/vs_N.dat' using 2:9 with points lt 6 pt 6 title 'spread (s.d.)', \
     tn(x) lt 2 title sprintf('N^{%.3f%s}  (χ^2/dof %s)', fit_mean_time_exponent, plus_minus(fit_mean_time_exponent_sigma, '%.3f'), \
         number_or_na(fit_mean_time_chi2_per_dof, '%.1f')), \
     tg(x) lt 3 title sprintf('Gumbel (N/m ≥ %.0f): a - τ ln N, τ = %.0f ± %.0f', fit_gumbel_min_regions, \
         fit_gumbel_tau, fit_gumbel_tau_sigma), \
     fit_gumbel_predicted_spread lt 3 dt 2 title sprintf('πτ/√6 = %.0f ± %.0f (measured %.0f ± %.0f)', \
         fit_gumbel_predicted_spread, fit_gumbel_predicted_spread_sigma, fit_gumbel_measured_spread, \
         fit_gumbel_measured_spread_sigma)
}
}

set offsets 0, 0, 0, 0
set xlabel 't'
set ylabel 'H(t) / N'
set yrange [*:*]
unset logscale x
set format x '%g'
set mxtics default
set key bottom right
plot for [i = 0:blocks - 1] datadir.'/hazard.dat' index i using 1:2 with points lt (i % 7 + 1) pt 7 ps 0.35 \
         title sprintf('N = %s', word(particles, i + 1))
unset multiplot
