# Fig. 4 of Ben-Naim et al. (1999): the mass-weighted velocity distribution
# P(v,t) rescaled as Phi(z) = t^(-1/3) P(v,t), z = v t^(1/3), for r = 0, 0.5, 0.9
# at three times (nine curves), against the exact sticky-gas Phi(z) (Frachebourg,
# Martin & Piasecki 2000; tail ~ exp(-z^3/2)) and a Gaussian of the same variance.
load styledir.'/style.gp'
load theorydir.'/constants.gp'
load datadir.'/collapse.gp'
set title sprintf('Fig. 4: scaling of the velocity distribution  (%s)', fidelity_note)
set xlabel 'scaled velocity z = (v - ⟨v⟩) t^{1/3}'
set ylabel 'Φ(z) = t^{-1/3} P(v, t)'
set logscale y
set format y "10^{%L}"
set xrange [-3.2:3.2]
set yrange [1e-5:2]
set key top right
set label 1 sprintf("scaling exponent β = %.3f%s (1/3 expected)\ncollapse distance at β = 1/3: %.2g", \
    collapse_beta, plus_minus(collapse_beta_sigma, '%.3f'), collapse_distance_at_one_third) at graph 0.03, graph 0.95 left font ',10'
# Nine blocks in the order r = 0, 0.5, 0.9, each at three increasing times.
rnames = '"r = 0" "r = 0.5" "r = 0.9"'
plot for [b = 0:8] datadir.'/phi.dat' index b using 1:($2 > 0 ? $2 : NaN) with points lt (b / 3 + 1) pt (7 + 2 * (b % 3)) ps 0.6 \
         title (b % 3 == 0 ? word(rnames, b / 3 + 1).', three times' : ''), \
     theorydir.'/phi.dat' using 1:2 with lines lc rgb '#000000' lw 2 title 'exact sticky gas', \
     theorydir.'/phi.dat' using 1:3 with lines lt 8 title sprintf('Gaussian, same variance κ = %.4f', exact_kappa)
