#!/usr/bin/env bash
# stamp_coverage_test.sh BUILD_DIR SOURCE_DIR SIM_DIRECTORIES TAIL_DIRECTORIES
# Simulations are stale exactly when what decides their numbers changes. They
# depend on BUILD_DIR/shockgas-sim.stamp, a hash over the simulator's rooms
# (SIM_DIRECTORIES: sim/model, sim/io, sim/engines, sim/run), and fig_tail's
# sampler on shockgas-tail.stamp (TAIL_DIRECTORIES: sim/tail, sim/model, sim/io);
# both "|"-separated, as the top-level CMakeLists.txt sets them. Checks:
#  1. the stamp's record of hashed files holds every file git tracks in those
#     rooms, each with its current SHA-256;
#  2. the programs record the same hash as simulator_sha256, which --resume
#     compares, so a checkpoint continues exactly when its simulation is not stale;
#  3. in a copy of the tree, edits that do not decide a simulation's numbers (a
#     program's help text, the Burgers solver, the suggestions, the tail
#     sampler, an editor's leftovers) leave the simulator's hash as it is, and
#     edits that do (the collision rule, an engine, the ensemble driver, the
#     output writer) change it; the tail sampler's hash moves with the sampler
#     and not with an engine.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
build=$1 source=$2 sim_directories=$3 tail_directories=$4
fail() { echo "FAIL: $*"; exit 1; }
cmake --build "$build" --target shockgas_sim_stamp >/dev/null || fail "building shockgas_sim_stamp"
record="$build/shockgas-sim.stamp.files"
[ -s "$record" ] || fail "no $record"
cd "$source" || exit 1
rooms=()
IFS='|' read -ra directories <<<"$sim_directories"
for d in "${directories[@]}"; do rooms+=("${d#"$source"/}"); done
tracked=$(git ls-files "${rooms[@]}")
[ -n "$tracked" ] || fail "git lists no simulator sources in $source (${rooms[*]})"
count=0
for f in $tracked; do
  count=$((count + 1))
  line="$(sha256sum "$f" | cut -d' ' -f1)  $f"
  grep -qxF "$line" "$record" || fail "$f (with its current content) is not in the stamp"
done

work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
"$build/bin/shockgas-sim" -N 10 -t 1 -q -o "$work/run.h5" 2>/dev/null || fail "a tiny run failed"
"$build/bin/shockgas-dump" gnuplot-vars "$work/run.h5" / --prefix run --output "$work/root.gp" || fail "dump"
recorded=$(sed -n 's/^run_simulator_sha256 = "\([0-9a-f]*\)"$/\1/p' "$work/root.gp")
stamp=$(cat "$build/shockgas-sim.stamp")
[ "$recorded" = "$stamp" ] || fail "the run records simulator_sha256 '$recorded', the stamp is '$stamp'"

# A copy of the tracked tree, hashed with the stamp's own script and the build's directory lists.
copy=$work/copy
git ls-files -z | (mkdir -p "$copy" && cd "$source" && xargs -0 cp --parents -t "$copy") || fail "copying the tree"
hash_of() {  # hash_of DIRECTORIES: the stamp of the copy
  cmake -DSOURCE_DIR="$copy" "-DDIRECTORIES=${1//"$source"/"$copy"}" -DCOMPILER_INFO=test -DSTAMP="$work/copy.stamp" \
        -P "$source/cmake/SourceStamp.cmake" && cat "$work/copy.stamp"
}
sim_clean=$(hash_of "$sim_directories") || fail "hashing the copy"
tail_clean=$(hash_of "$tail_directories") || fail "hashing the copy's tail sampler"
edit() { printf '\n// an edit\n' >>"$copy/$1" || fail "editing $1"; }
unedit() { (cd "$source" && cp "$1" "$copy/$1") || fail "restoring $1"; }

# Not the simulation: each leaves the simulator's hash as it was.
for f in analysis/app/shockgas_dump.cpp analysis/src/dump.cpp sim/app/shockgas_sim.cpp analysis/src/burgers.cpp sim/cli/src/suggest.cpp \
         sim/tail/src/tail_sampler.cpp; do
  [ -f "$copy/$f" ] || fail "no $f in the tree: update this test's list"
  edit "$f"
  [ "$(hash_of "$sim_directories")" = "$sim_clean" ] || fail "editing $f changed the simulator's hash"
  unedit "$f"
done
touch "$copy/sim/run/src/.checkpoint.cpp.swp" "$copy/sim/run/src/checkpoint.cpp~" "$copy/sim/io/src/output.cpp.orig"
[ "$(hash_of "$sim_directories")" = "$sim_clean" ] || fail "editor leftovers changed the hash"

# The simulation: each changes it.
for f in sim/model/include/shockgas/model/collision.hpp sim/engines/src/event_engine.cpp sim/run/src/ensemble.cpp \
         sim/io/src/output.cpp sim/engines/CMakeLists.txt; do
  [ -f "$copy/$f" ] || fail "no $f in the tree: update this test's list"
  edit "$f"
  [ "$(hash_of "$sim_directories")" != "$sim_clean" ] || fail "editing $f did not change the simulator's hash"
  unedit "$f"
done

# The tail sampler's own stamp: its room moves it, an engine does not.
edit sim/tail/src/tail_sampler.cpp
[ "$(hash_of "$tail_directories")" != "$tail_clean" ] || fail "editing the sampler did not change its hash"
unedit sim/tail/src/tail_sampler.cpp
edit sim/engines/src/event_engine.cpp
[ "$(hash_of "$tail_directories")" = "$tail_clean" ] || fail "editing an engine changed the sampler's hash"
echo "ok: the stamp covers all $count simulator sources, the programs record it as simulator_sha256, and edits" \
     "outside the simulation's rooms leave it while edits inside change it"
