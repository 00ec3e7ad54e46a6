# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 4 of Ben-Naim et al. (1999): the mass-weighted velocity distribution
# P(v,t) rescaled as Phi(z) = t^(-1/3) P(v,t), z = v t^(1/3), for r = 0, 0.5, 0.9
# at three times (nine curves), against the exact sticky-gas Phi(z) (Frachebourg,
# Martin & Piasecki 2000; tail ~ exp(-z^3/2)) and a Gaussian of the same variance.
load styledir.'/style.gp'
load theorydir.'/constants.gp'
load datadir.'/collapse.gp'
# A caller that draws another variant (fig4_sticky.gp) names it with subtitle, shown after the title.
if (!exists('subtitle')) subtitle = ''
set title sprintf('Fig. 4: scaling of the velocity distribution%s  (%s)', subtitle, fidelity_note)
set xlabel 'scaled velocity z = (v - ⟨v⟩) t^{1/3}'
set ylabel 'Φ(z) = t^{-1/3} P(v, t)'
set logscale y
set format y "10^{%L}"
set xrange [-3.2:3.2]
set yrange [1e-5:2]
# Below the curves, where no point lies (Φ < 1e-4 at |z| < 1).
set key bottom center
set label 1 sprintf("scaling exponent β = %.3f%s (1/3 expected)\ncollapse distance at β = 1/3: %.2g", \
    collapse_beta, plus_minus(collapse_beta_sigma, '%.3f'), collapse_distance_at_one_third) at graph 0.03, graph 0.95 left font ',10'
# Nine blocks in the order r = 0, 0.5, 0.9, each at three increasing times. A caller that passes other
# runs (tools/provisional-fig4 leaves out an r with no finished part) names them with -e: rnames, one
# quoted label per run in the order of the blocks; rtypes, each run's line type; ntimes, the blocks per run.
if (!exists('rnames')) rnames = '"r = 0" "r = 0.5" "r = 0.9"'
if (!exists('rtypes')) rtypes = '1 2 3'
if (!exists('ntimes')) ntimes = 3
times_note = (ntimes == 3 ? ', three times' : sprintf(', %d times', ntimes))
# The marker says the time: the times of the first run's blocks, from their comment lines in phi.dat
# ("# r=0 t=1000"; every run has the same times), each named in the key with its marker.
in_single_quotes(s) = strstrt(s, "'") == 0 ? s : s[1:strstrt(s, "'") - 1]."'\\''".in_single_quotes(s[strstrt(s, "'") + 1:])
block_times = system(sprintf("sed -n 's/^# .*t=\\([0-9.e+-]*\\)$/\\1/p' '%s' | head -n %d", \
                             in_single_quotes(datadir.'/phi.dat'), ntimes))
plot for [b = 0:words(rnames) * ntimes - 1] datadir.'/phi.dat' index b using 1:($2 > 0 ? $2 : NaN) with points \
         lt (word(rtypes, b / ntimes + 1) + 0) pt (7 + 2 * (b % ntimes)) ps 0.6 \
         title (b % ntimes == 0 ? word(rnames, b / ntimes + 1).times_note : ''), \
     for [k = 1:ntimes] keyentry with points lc rgb '#555555' pt (7 + 2 * (k - 1)) ps 0.6 \
         title sprintf('t = %s', word(block_times, k)), \
     theorydir.'/phi.dat' using 1:2 with lines lc rgb '#000000' lw 2 title 'exact sticky gas', \
     theorydir.'/phi.dat' using 1:3 with lines lt 8 title sprintf('Gaussian, same variance κ = %.4f', exact_kappa)
