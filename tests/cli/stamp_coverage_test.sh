#!/usr/bin/env bash
# stamp_coverage_test.sh BUILD_DIR SOURCE_DIR
# Simulations are stale when the simulator's sources change: they depend on
# BUILD_DIR/shockgas-sim.stamp, a hash over every file in sim/src, sim/include
# and sim/app (cmake/SourceStamp.cmake). Builds the stamp as the figure build
# does and checks that its record of hashed files (shockgas-sim.stamp.files)
# holds every file git tracks there, each with its current SHA-256. Until this
# test existed the stamp hashed no file at all, and no change to the simulator
# ever reran a simulation.
set -u
build=$1 source=$2
cmake --build "$build" --target shockgas_sim_stamp >/dev/null || { echo "FAIL: building shockgas_sim_stamp"; exit 1; }
record="$build/shockgas-sim.stamp.files"
[ -s "$record" ] || { echo "FAIL: no $record"; exit 1; }
cd "$source" || exit 1
tracked=$(git ls-files sim/src sim/include sim/app)
[ -n "$tracked" ] || { echo "FAIL: git lists no simulator sources in $source"; exit 1; }
missing=0
count=0
for f in $tracked; do
  count=$((count + 1))
  line="$(sha256sum "$f" | cut -d' ' -f1)  $f"
  grep -qxF "$line" "$record" || { echo "FAIL: $f (with its current content) is not in the stamp"; missing=1; }
done
[ "$missing" -eq 0 ] || exit 1
# The programs compile in the same hash (cmake/BuildInfo.cmake) and record it as
# simulator_sha256, which --resume compares: one computation, so a checkpoint is
# continued exactly when the simulation it belongs to is not stale.
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
"$build/sim/shockgas-sim" -N 10 -t 1 -q -o "$work/run.h5" 2>/dev/null || { echo "FAIL: a tiny run failed"; exit 1; }
"$build/sim/shockgas-dump" gnuplot-vars "$work/run.h5" / --prefix run --output "$work/root.gp" || { echo "FAIL: dump"; exit 1; }
recorded=$(sed -n 's/^run_simulator_sha256 = "\([0-9a-f]*\)"$/\1/p' "$work/root.gp")
stamp=$(cat "$build/shockgas-sim.stamp")
[ "$recorded" = "$stamp" ] || { echo "FAIL: the run records simulator_sha256 '$recorded', the stamp is '$stamp'"; exit 1; }
# An editor's leftovers beside the sources (a swap file, a backup) are not sources:
# they must not change the hash, or opening checkpoint.cpp in vim across a
# paper-tier stop and start would make every run in progress another simulator's.
# Checked on a copy, with the stamp's own script.
mkdir -p "$work/copy/sim" && cp -r sim/src sim/include sim/app "$work/copy/sim/" || { echo "FAIL: copy"; exit 1; }
stamp_of_copy() {
  cmake -DSOURCE_DIR="$work/copy" "-DDIRECTORIES=$work/copy/sim/src|$work/copy/sim/include|$work/copy/sim/app" \
        -DCOMPILER_INFO=test -DSTAMP="$work/copy.stamp" -P "$source/cmake/SourceStamp.cmake" && cat "$work/copy.stamp"
}
clean=$(stamp_of_copy) || { echo "FAIL: hashing the copy"; exit 1; }
touch "$work/copy/sim/src/.checkpoint.cpp.swp" "$work/copy/sim/src/checkpoint.cpp~" "$work/copy/sim/src/output.cpp.orig"
[ "$(stamp_of_copy)" = "$clean" ] || { echo "FAIL: editor leftovers changed the hash"; exit 1; }
echo "// a change" >>"$work/copy/sim/src/checkpoint.cpp"
[ "$(stamp_of_copy)" != "$clean" ] || { echo "FAIL: a changed source did not change the hash"; exit 1; }
echo "ok: the stamp covers all $count simulator sources and no editor leftovers, and the programs record it as simulator_sha256"
