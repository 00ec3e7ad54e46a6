#!/usr/bin/env bash
# readme_tables_test.sh BUILD_DIR PYTHON WORK_DIR
# tools/fidelity_report.py --readme on a miniature pipeline tree (tiny runs
# under the figures' file names): every row it can fill comes out in the
# README's form (claim, quick tier, paper tier, paper / theory) with the
# numbers of the files, so the README's results table can be regenerated from
# a build instead of typed.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
build=$1 python=$2 work=$3
sim=$build/bin/shockgas-sim analyze=$build/bin/shockgas-analyze
base=$work/paper_targets/quick
rm -rf "$work" && mkdir -p "$base/fig1" "$base/fig4" "$base/fig5"
fail() { echo "FAIL: $*"; echo "output was:"; echo "$out"; exit 1; }
"$sim" -N 3000 -r 0 -t 3000 -R 3 -q -o "$base/fig1/r0.h5" 2>/dev/null
"$analyze" decay "$base/fig1/r0.h5" -o "$base/fig1/r0.decay.h5" >/dev/null
"$sim" -N 3000 -r 0 -t 1000 -R 2 --histogram-times 100,1000 -q -o "$base/fig4/r0.h5" 2>/dev/null
"$analyze" scaling "$base/fig4/r0.h5" -o "$base/fig4/scaling.h5" >/dev/null
"$sim" -N 3000 -r 0.9 -d 1e-3 -t 1000 -R 1 --snapshot-times 1000 -q -o "$base/fig5/profile.h5" 2>/dev/null
"$analyze" shocks "$base/fig5/profile.h5" -o "$base/fig5/shocks.h5" >/dev/null
out=$("$python" "$(dirname "$0")/../../tools/fidelity_report.py" "$work" quick --readme)
exponent=$("$build/bin/shockgas-dump" gnuplot-vars "$base/fig1/r0.decay.h5" /decay --prefix d | sed -n 's/^d_exponent = //p')
echo "$out" | grep -q '^| claim | quick tier | paper tier | paper / theory |$' || fail "no table header"
echo "$out" | grep -Eq "^\| P1: T ~ t\^−α, r = 0 \| α = $(printf '%.3f' "$exponent") ± [0-9.]+ ± .* \(N = 3·10³, 3 real\., t ∈ \[100, .*\]\) \| .* \| 0\.67 / 2/3 \|$" \
  || fail "no P1 row with the file's exponent $exponent"
echo "$out" | grep -Eq '^\| P7: .*, best β \| β = [0-9.]+ ± [0-9.]+ \(2 histograms\) \| .* \| 1/3 \|$' || fail "no P7 row"
echo "$out" | grep -Eq '^\| P9: shocks at t = 10³ \(N = 3·10³, r = 0.9, δ = 10⁻³\) \| [0-9]+ \|' || fail "no P9 row"
[ "$(echo "$out" | grep -c '^| P')" -eq 5 ] || fail "expected 5 rows (P1, P7, P7/P8, P9 twice)"
# The paper tier's cell of a row comes from the source tree's README, where it has that claim.
paper=$(sed -n 's/^| P1: T ~ t^−α, r = 0 | [^|]* | \([^|]*\) | .*/\1/p' "$(dirname "$0")/../../README.md")
[ -n "$paper" ] && { echo "$out" | grep -qF "| $paper | 0.67 / 2/3 |" || fail "the P1 row lacks the README's paper-tier cell '$paper'"; }
echo "ok"; echo "$out"
