# SPDX-License-Identifier: GPL-3.0-or-later
# A look at any one run (tools/shockgas-look): T(t) with the fitted power law
# and, when the run stored histograms, the rescaled P(v,t) of every histogram
# time. Variables (-e): tfile (T(t) data of shockgas-analyze decay --data),
# varsfile (the fit as gnuplot variables, or '' when there is no fit), phifile
# (Phi(z) data of shockgas-analyze scaling --data, or ''), labels (one word
# per histogram block, e.g. t=1000), run (the run's name for the title),
# outbase, styledir, format.
fidelity = 'own run'
load styledir.'/style.gp'
have_fit = (varsfile ne '')
if (have_fit) { load varsfile }
if (phifile ne '') {
    # Two panels side by side: a wider canvas.
    if (format eq 'svg') {
        set terminal svg size 1600,700 font 'Sans,12' enhanced
    } else {
        set terminal pngcairo size 1600,700 font 'Sans,12'
    }
    set output outbase.'.'.format
    set multiplot layout 1,2 title run
}
set logscale xy
@decades
set xlabel 't'
set ylabel 'T(t)'
set key bottom left
set title 'temperature' . (have_fit ? sprintf(': T ∝ t^{−α}, α = %.3f%s on [%s, %s]', fit_exponent, plus_minus(fit_exponent_sigma, '%.3f'), short_number(fit_t_lo), short_number(fit_t_hi)) : ' (no fit)')
if (have_fit) {
    set arrow 1 from fit_t_lo, graph 0 to fit_t_lo, graph 1 nohead lc rgb '#999999' dt 3
    set arrow 2 from fit_t_hi, graph 0 to fit_t_hi, graph 1 nohead lc rgb '#999999' dt 3
    plot tfile using 1:2:3 with yerrorbars lt 3 pt 7 ps 0.5 title 'ensemble mean ± σ', \
         [fit_t_lo:fit_t_hi] fit_prefactor * x**(-fit_exponent) with lines lt 2 lw 2.5 \
         title sprintf('fit: %.3g t^{−%.3f}', fit_prefactor, fit_exponent)
} else {
    plot tfile using 1:2:3 with yerrorbars lt 3 pt 7 ps 0.5 title 'ensemble mean ± σ'
}
if (phifile ne '') {
    unset arrow
    unset logscale x
    set logscale y
    set format x '%g'
    set xlabel 'z = (v - V) t^{1/3}'
    set ylabel 'Φ(z) = t^{-1/3} P(v, t)'
    set key top right
    set title 'velocity distribution, rescaled (one curve per histogram time)'
    # One block per histogram time, each labelled; the file ends in two blank lines, which
    # stats counts as one more (empty) block, so the labels give the count where they exist.
    stats phifile using 1 nooutput
    blocks = words(labels) > 0 ? words(labels) : STATS_blocks
    # 't=1000' in the key as 't = 1000'.
    time_label(w) = (w[1:2] eq 't=') ? 't = '.w[3:] : w
    plot for [b = 0:blocks - 1] phifile index b using 1:($2 > 0 ? $2 : 1/0) with linespoints \
         lt (b % 7) + 1 pt 7 ps 0.4 title time_label(word(labels, b + 1))
    unset multiplot
}
