#!/usr/bin/env bash
# plots_without_fits_test.sh ANALYZE DUMP GNUPLOT FIGURES_DIR WORKDIR
# figures/fig_collapse.gp and fig_crossovers.gp draw whatever shockgas-analyze
# collapse and crossover could measure. Where the fits across inputs are n/a
# (an input of one realization has no sigma to weigh by; one input alone has
# no slope), the results file holds a note instead of the fitted numbers, and
# the scripts must draw the points and name the note, not stop on gnuplot's
# "undefined variable".
# WORKDIR holds the analyze fixture's runs: col06.h5 (three realizations,
# r = 0.6), col_one.h5 (one, r = 0.5), col4k.h5 (three, N = 4000), col300.h5
# (three, N = 300: N/m = 30, below the Gumbel fit's 50 regions), e05.h5
# (four realizations, r = 0.9), e10_one.h5 (one, r = 0.8).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
analyze=$1 dump=$2 gnuplot=$3 figures=$4 work=$5
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
plot() {  # plot FIGURE DIR: gnuplot draws DIR/FIGURE.png from the files in DIR, or the test fails
    "$gnuplot" -e "datadir='$2'; outbase='$2/$1'; styledir='$figures'; theorydir='.'; fidelity='test'; format='png'" \
        "$figures/$1.gp" 2> "$2/gnuplot.err" || { cat "$2/gnuplot.err"; fail "$2: gnuplot failed"; }
    [ -s "$2/$1.png" ] || fail "$2: no figure"
}
draw() {  # draw NAME EPS_INPUTS... -- N_INPUTS...
    local name=$1; shift
    local eps=() n=()
    while [ "$1" != "--" ]; do eps+=("$1"); shift; done
    shift; n=("$@")
    local dir="fig_collapse_$name"
    rm -rf "$dir" && mkdir "$dir" || fail "$name: cannot make $dir"
    "$analyze" collapse --vs eps "${eps[@]}" -o "$dir/vs_eps.h5" --data "$dir/vs_eps.dat" >/dev/null \
        || fail "$name: collapse --vs eps failed"
    "$dump" gnuplot-vars "$dir/vs_eps.h5" /time_forms --recursive --prefix time --output "$dir/time_forms.gp" \
        || fail "$name: dump time_forms"
    "$dump" gnuplot-vars "$dir/vs_eps.h5" /mass_forms --recursive --prefix mass --output "$dir/mass_forms.gp" \
        || fail "$name: dump mass_forms"
    "$analyze" collapse --vs N "${n[@]}" -o "$dir/vs_N.h5" --data "$dir/vs_N.dat" --hazard "$dir/hazard.dat" \
        >/dev/null || fail "$name: collapse --vs N failed"
    "$dump" gnuplot-vars "$dir/vs_N.h5" /first_collapse --prefix fit --output "$dir/vs_N.gp" \
        || fail "$name: dump first_collapse"
    plot fig_collapse "$dir"
    echo "$name: drawn"
}
draw_crossovers() {  # draw_crossovers NAME NOTE_REGEX INPUTS...: the note stored, then the figure
    local dir="fig_crossovers_$1" note=$2; shift 2
    rm -rf "$dir" && mkdir "$dir" || fail "cannot make $dir"
    "$analyze" crossover "$@" -o "$dir/crossovers.h5" --data "$dir/crossovers.dat" >/dev/null \
        || fail "$dir: crossover failed"
    "$dump" gnuplot-vars "$dir/crossovers.h5" /scaling_in_eps --prefix fit --output "$dir/crossovers.gp" \
        || fail "$dir: dump scaling_in_eps"
    grep -q "$note" "$dir/crossovers.gp" || fail "$dir: no fit_note matching $note"
    plot fig_crossovers "$dir"
}
# The fits are n/a, so the notes stand where the numbers would: the figure
# has only them to go on.
draw no_sigma col06.h5 col_one.h5 -- col4k.h5 col_one.h5
grep -q '^time_note = "the forms against eps are weighted by each input' fig_collapse_no_sigma/time_forms.gp \
    || fail "no time_note"
grep -q '^fit_note = "the fits across N are weighted by each input' fig_collapse_no_sigma/vs_N.gp || fail "no fit_note"
draw one_input col_one.h5 -- col_one.h5
grep -q '^time_note = "one input: give runs of 2 or more eps"$' fig_collapse_one_input/time_forms.gp \
    || fail "one input: no time_note"
grep -q '^fit_note = "one input: give runs of 2 or more N"$' fig_collapse_one_input/vs_N.gp || fail "one input: no fit_note"
# The fits across N stand but the Gumbel fit alone is n/a: only col.h5 has N/m >= 50.
draw gumbel_na col06.h5 col.h5 -- col300.h5 col.h5
grep -q '^fit_gumbel_note = "1 run with N/<m> >= 50; the Gumbel fit needs 2 N"$' fig_collapse_gumbel_na/vs_N.gp \
    || fail "Gumbel n/a: no fit_gumbel_note"
grep -q '^fit_mean_time_exponent = ' fig_collapse_gumbel_na/vs_N.gp || fail "Gumbel n/a: the fits across N are missing"

# fig_crossovers, its fits n/a for the same reason.
draw_crossovers no_sigma '^fit_note = "the fits over eps are weighted by each input' e05.h5 e10_one.h5
# One input has no slope: the note says so (crossover writes a note where it writes no fits).
draw_crossovers one_input '^fit_note = "one input: give runs of 2 or more eps"$' e05.h5
echo "fig_collapse and fig_crossovers drawn where their fits are n/a"
