# SPDX-License-Identifier: GPL-3.0-or-later
# Shared style for every shockgas figure. CMake runs each figure script twice,
# with format = 'png' and format = 'pdf'; loading this file sets the terminal
# and the output file, so the scripts themselves only plot. format = 'svg'
# draws the same as text (the tests read its titles and keys).
# Variables passed by CMake (-e): datadir, outbase, styledir, theorydir,
# fidelity, format, version_program.
set encoding utf8
if (format eq 'pdf') {
    set terminal pdfcairo size 6in,4.5in font 'Sans,9'
} else {
    if (format eq 'svg') {
        set terminal svg size 1000,760 font 'Sans,12' enhanced
    } else {
        set terminal pngcairo size 1000,760 font 'Sans,12'
    }
}
set output outbase.'.'.format
set termoption enhanced
set border lw 1.2
set grid lt 1 lc rgb '#dddddd' lw 0.8
# width 1: gnuplot sizes the box from a character count, and a label of wide characters (digits,
# κ, ±) reached its left edge.
set key top right box opaque samplen 2.5 spacing 1.15 width 1 font ',10'
set tics out nomirror
set mxtics 10
set mytics 10

# Okabe-Ito colour-blind-safe palette.
set linetype 1 lc rgb '#000000' lw 2 pt 7 ps 0.6
set linetype 2 lc rgb '#E69F00' lw 2 pt 5 ps 0.6
set linetype 3 lc rgb '#0072B2' lw 2 pt 9 ps 0.7
set linetype 4 lc rgb '#D55E00' lw 2 pt 11 ps 0.7
set linetype 5 lc rgb '#009E73' lw 2 pt 13 ps 0.7
set linetype 6 lc rgb '#CC79A7' lw 2 pt 6 ps 0.7
set linetype 7 lc rgb '#56B4E9' lw 2 pt 4 ps 0.7
set linetype 8 lc rgb '#999999' lw 1.5 dt 2
set linetype cycle 8

decades = 'set format x "10^{%L}"; set format y "10^{%L}"'
# The title's note: the fidelity and the version of the tools that drew the figure (git describe,
# as every output file records it), so that a figure away from its build says what made it.
# version_program (CMake: shockgas-dump) prints "shockgas-dump <version>".
shockgas_version = exists('version_program') ? word(system(sprintf("'%s' --version", version_program)), 2) : ''
fidelity_note = (shockgas_version eq '') ? sprintf('%s fidelity', fidelity) \
                                         : sprintf('%s fidelity, shockgas %s', fidelity, shockgas_version)
# ' ± sigma' printed with format f, or ' ± n/a' where shockgas-analyze stored NaN
# (one or two realizations; its note in the results file says why).
plus_minus(sigma, f) = (sigma == sigma) ? sprintf(' ± '.f, sigma) : ' ± n/a'
# A time such as a fit window's bound, as it is worth reading: to the unit from 100 to 10^6
# (10^2.5 = 316.228 as 316, 3162.28 as 3162), else three significant digits (31.6, 0.316, 3.16e+06).
short_number(x) = (abs(x) >= 100 && abs(x) < 1e6) ? sprintf('%.0f', x) : sprintf('%.3g', x)
# A number printed with format f, or 'n/a' where it is NaN (a chi2/dof of two points).
number_or_na(x, f) = (x == x) ? sprintf(f, x) : 'n/a'
