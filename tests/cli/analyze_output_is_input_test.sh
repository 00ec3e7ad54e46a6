#!/usr/bin/env bash
# analyze_output_is_input_test.sh ANALYZE WORKDIR
# No output of any shockgas-analyze subcommand (-o, --data, --scan, --hazard,
# --curves) may be written over one of its inputs, nor two outputs over one
# file: each such run is refused before any work, with one line and status 2,
# and the input is left byte for byte as it was. WORKDIR holds the fixture's
# runs a.h5 (two realizations, r = 0.5) and e05.h5 (r = 0.9).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
analyze=$1 work=$2
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
cp a.h5 in.h5 || exit 1
rm -f link.h5 out.h5 t.dat && ln in.h5 link.h5 || exit 1
reference=$(sha256sum <in.h5)

# refused REGEX ARGS...: the run must fail as bad input, naming the problem,
# with in.h5 unchanged and no out.h5 or t.dat written.
refused() {
  local regex=$1 stderr status
  shift
  stderr=$("$analyze" "$@" 2>&1 >/dev/null)
  status=$?
  [ "$status" -eq 2 ] || fail "'$*': exit status $status, expected 2; stderr: $stderr"
  [ "$(printf '%s\n' "$stderr" | wc -l)" -eq 1 ] || fail "'$*': not one line on stderr: $stderr"
  printf '%s\n' "$stderr" | grep -Eq -- "$regex" || fail "'$*': stderr does not match /$regex/: $stderr"
  [ "$(sha256sum <in.h5)" = "$reference" ] || fail "'$*': the input in.h5 changed"
  [ ! -e out.h5 ] && [ ! -e t.dat ] || fail "'$*': an output was written"
  echo "ok: $*: $stderr"
}
is_input="output '.*' is the input '.*in.h5': it would be overwritten"
refused "$is_input" decay in.h5 -o in.h5 --t-lo 1 --t-hi 100
refused "$is_input" decay in.h5 -o out.h5 --data in.h5 --t-lo 1 --t-hi 100
refused "$is_input" decay in.h5 -o out.h5 --scan ./in.h5 --t-lo 1 --t-hi 100
refused "$is_input" decay in.h5 --data-only --data in.h5
refused "$is_input" decay in.h5 -o link.h5 --t-lo 1 --t-hi 100  # a hard link is the same file
refused "$is_input" crossover e05.h5 in.h5 -o in.h5
refused "$is_input" crossover e05.h5 in.h5 -o out.h5 --data in.h5
refused "$is_input" scaling in.h5 -o out.h5 --data in.h5
refused "$is_input" shocks in.h5 -o in.h5
refused "$is_input" collapse in.h5 -o out.h5 --data in.h5
refused "$is_input" collapse in.h5 --vs N -o out.h5 --hazard in.h5
refused "$is_input" compare in.h5 e05.h5 -o out.h5 --curves in.h5
refused "$is_input" compare e05.h5 in.h5 -o out.h5 --data in.h5
refused "$is_input" far-tail in.h5 -o in.h5
refused "--data and --scan name the same file '.*t.dat': one would overwrite the other" \
  decay in.h5 -o out.h5 --data t.dat --scan ./t.dat --t-lo 1 --t-hi 100
refused "-o and --data name the same file" crossover e05.h5 in.h5 -o out.h5 --data out.h5
rm -f link.h5 in.h5
