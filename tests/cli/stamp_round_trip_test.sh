#!/usr/bin/env bash
# stamp_round_trip_test.sh BUILD_DIR: a finished run is kept when the simulator's stamp is rewritten
# with the hash it had (a checkout of a commit with other simulator sources and back: make sees a
# newer stamp, while the run's numbers would come out the same), and simulated again when what it
# was made from differs (cmake/RunSimulation.cmake, the record <run>.h5.made).
#   1. build fig3; its run's record names the .args file and the stamp with their SHA-256;
#   2. overwrite the stamp with another hash: the build's stamp step writes the true one back, newer
#      than the run; the build must keep the run (the same bytes: a rerun writes another date);
#   3. alter the record and touch the stamp: the build must simulate again (other bytes).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
build=$1
fail() { echo "FAIL: $*"; exit 1; }
run="$build/paper_targets/quick/fig3/worldlines.h5"
stamp="$build/shockgas-sim.stamp"
cmake --build "$build" --target fig3 >/dev/null || fail "building fig3"
if [ ! -e "$run.made" ]; then  # a run made before records were kept: made again once, with its record
  touch "$stamp" && cmake --build "$build" --target fig3 >/dev/null || fail "building fig3 again"
fi
[ -s "$run.made" ] || fail "no record $run.made"
grep -q "  $build/paper_targets/quick/fig3/worldlines.args\$" "$run.made" || fail "the record names no .args: $(cat "$run.made")"
grep -q "^$(sha256sum "$stamp" | cut -d' ' -f1)  $stamp\$" "$run.made" || fail "the record lacks the stamp's hash"
before=$(sha256sum "$run" | cut -d' ' -f1)
sleep 1  # file times of a second's resolution must still tell the new stamp from the run
echo "0000000000000000000000000000000000000000000000000000000000000000" >"$stamp"
log=$(cmake --build "$build" --target fig3 2>&1) || { echo "$log"; fail "the build after the round trip"; }
[ "$(cat "$stamp")" != "0000000000000000000000000000000000000000000000000000000000000000" ] ||
  fail "the stamp step did not write the hash back"
[ "$stamp" -nt "$build/paper_targets/quick/fig3/worldlines.args" ] || fail "the stamp is not newer than the .args"
grep -q "worldlines.h5 was made from the same parameters and simulator sources: kept" <<<"$log" ||
  { echo "$log"; fail "the round trip did not keep the run"; }
[ "$(sha256sum "$run" | cut -d' ' -f1)" = "$before" ] || fail "the run was made again after the round trip"
[ "$stamp" -nt "$run" ] && fail "the kept run is still older than the stamp"
sleep 1
echo "0000000000000000000000000000000000000000000000000000000000000000  $stamp" >"$run.made"
touch "$stamp"
log=$(cmake --build "$build" --target fig3 2>&1) || { echo "$log"; fail "the build with another record"; }
grep -q ": kept" <<<"$log" && fail "a run whose record differs was kept"
[ "$(sha256sum "$run" | cut -d' ' -f1)" != "$before" ] || fail "a run whose record differs was not made again"
grep -q "^$(sha256sum "$stamp" | cut -d' ' -f1)  $stamp\$" "$run.made" || fail "the new record lacks the stamp's hash"
echo "ok"
