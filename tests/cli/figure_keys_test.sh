#!/usr/bin/env bash
# figure_keys_test.sh ANALYZE DUMP PYTHON SOURCE_DIR WORKDIR
# What the figures' keys and titles say, read from SVG (figures/style.gp, format = 'svg'):
#   - fig4 and fig4_sticky name the time of each marker ("t = 10", "t = 100": the marker shape is
#     the time, the colour the run; not only the runs);
#   - fig_tail draws the sampler in another colour than the exact curve (both black, the points
#     would vanish under the curve);
#   - shockgas-look names each histogram time "t = 10" and prints its fit window as 100 and 894
#     (not 894.427).
# WORKDIR holds the analyze fixture's runs: hist.h5 (N = 2000, r = 0.5, t = 1000, histograms at
# t = 10 and 100) and short_tail.h5 (a far tail of the sticky gas at t = 100).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
analyze=$1 dump=$2 python=$3 source=$4 work=$5
fail() { echo "FAIL: $*"; exit 1; }
out=$work/figure_keys
rm -rf "$out" && mkdir -p "$out/theory" "$out/bin" || exit 1
cd "$out" || exit 1
gnuplot=$(command -v gnuplot) || fail "no gnuplot"
"$python" "$source/python/exact_ballistic.py" --out-dir theory >/dev/null || fail "the exact theory did not build"
draw() {  # draw FIGURE DIR [GNUPLOT VARIABLES]: DIR/FIGURE.svg from the files in DIR
  "$gnuplot" -e "datadir='$2'; outbase='$2/$1'; styledir='$source/figures'; theorydir='$out/theory'; \
                 fidelity='test'; format='svg'; ${3:-}" "$source/figures/$1.gp" 2>"$2/$1.err" ||
    { cat "$2/$1.err"; fail "gnuplot could not draw $1"; }
}
# The key's texts of an SVG, one a line.
key_texts() { sed -n 's/.*<text><tspan[^>]*>\([^<]*\)<\/tspan><\/text>.*/\1/p' "$1"; }
expect_key() {  # expect_key SVG TEXT...
  local svg=$1; shift
  for text in "$@"; do
    key_texts "$svg" | grep -qxF "$text" || fail "$svg: no '$text' in the key, which reads: $(key_texts "$svg" | tr '\n' '|')"
  done
}

# fig4: hist.h5 as one run of two times; fig4_sticky: three runs (hist.h5 thrice) of two times.
mkdir fig4 && "$analyze" scaling "$work/hist.h5" -o fig4/scaling.h5 --data fig4/phi.dat >/dev/null &&
  "$dump" gnuplot-vars fig4/scaling.h5 /collapse --prefix collapse --output fig4/collapse.gp || fail "fig4's data"
draw fig4 "$out/fig4" "rnames='\"r = 0.5\"'; rtypes='2'; ntimes=2"
expect_key fig4/fig4.svg "r = 0.5, 2 times" "t = 10" "t = 100"
mkdir fig4_sticky && "$analyze" scaling "$work/hist.h5" "$work/hist.h5" "$work/hist.h5" -o fig4_sticky/scaling.h5 \
    --data fig4_sticky/phi.dat >/dev/null &&
  "$dump" gnuplot-vars fig4_sticky/scaling.h5 /collapse --prefix collapse --output fig4_sticky/collapse.gp ||
  fail "fig4_sticky's data"
draw fig4_sticky "$out/fig4_sticky" "ntimes=2"
expect_key fig4_sticky/fig4_sticky.svg "r = 0.9, sticky below δ, 2 times" "t = 10" "t = 100"
echo "fig4, fig4_sticky: the key names both times"

# fig_tail: the colour of each plot's first line or point, by its key title.
mkdir fig_tail && "$analyze" far-tail "$work/short_tail.h5" -o fig_tail/gamma.h5 --data fig_tail/tail.dat >/dev/null &&
  "$dump" gnuplot-vars fig_tail/gamma.h5 /far_tail --prefix tail --output fig_tail/gamma.gp || fail "fig_tail's data"
draw fig_tail "$out/fig_tail"
colour_of() {  # colour_of SVG TITLE: the first colour drawn under that key title (a line's stroke='...' or
  # a marker's color='...'; the group's own stroke="..." is the colour before it)
  awk -v title="<title>$2</title>" 'index($0, title) { inside = 1; next }
    inside && match($0, /(stroke|color)=\047rgb\([^)]*\)/) { print substr($0, RSTART, RLENGTH); exit }' "$1" |
    sed 's/.*rgb/rgb/; s/ //g'
}
sampler=$(colour_of fig_tail/fig_tail.svg "sampler (± jackknife)") exact=$(colour_of fig_tail/fig_tail.svg exact)
[ -n "$sampler" ] && [ -n "$exact" ] || fail "fig_tail: no colour for the sampler ('$sampler') or the exact curve ('$exact')"
[ "$sampler" != "$exact" ] || fail "fig_tail: the sampler is drawn in the exact curve's colour, $exact"
echo "fig_tail: sampler $sampler, exact $exact"

# shockgas-look, through a gnuplot first on PATH that draws each figure twice: as asked, and as SVG
# (while shockgas-look's temporary files are there).
cat >bin/gnuplot <<EOF
#!/bin/bash
"$gnuplot" "\$@" || exit
[ "\$1" = -e ] || exit 2
exec "$gnuplot" -e "\${2/"format='png'"/"format='svg'"}; outbase='$out/look'" "\${@:3}"
EOF
chmod +x bin/gnuplot
ln -s "$analyze" bin/shockgas-analyze && ln -s "$dump" bin/shockgas-dump || exit 1
PATH="$out/bin:$PATH" "$source/tools/shockgas-look" "$work/hist.h5" -o "$out/look.png" >look.log 2>&1 ||
  { cat look.log; fail "shockgas-look"; }
[ -s look.png ] && [ -s look.svg ] || fail "shockgas-look drew no look.png and look.svg: $(cat look.log)"
expect_key look.svg "t = 10" "t = 100"
grep -q 'on \[100, 894\]' look.svg || fail "look.svg: the fit window is not [100, 894]: $(grep -o 'on \[[^]]*\]' look.svg)"
echo "shockgas-look: the key names both times, the window reads [100, 894]"
echo "ok"
