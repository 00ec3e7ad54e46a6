#!/usr/bin/env bash
# step_command_test.sh BUILD_DIR
# A figure's own steps (analyses, dumps, the far-tail sampler) rerun when their
# command changes, not only when an input is newer (make tracks no command
# lines): each depends on <first output>.command, which configuring rewrites
# when the step's arguments change (shockgas_step in paper_targets/pipeline.cmake),
# so that an option edited in a <figure>.cmake file, or a run taken out of an
# aggregate's inputs, does not leave the outputs stale. Checked on Fig. 3's world-line
# dump (its run is under a second): built, up to date, then its command record
# changed -> the step reruns; configuring restores the record -> it reruns again,
# and then nothing does.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
build=$1
step='\[fig3\] world lines'
record="$build/paper_targets/quick/fig3/worldlines.dat.command"
build_fig3() { cmake --build "$build" --target fig3 2>&1; }
build_fig3 >/dev/null || { echo "FAIL: building fig3"; exit 1; }
[ -s "$record" ] || { echo "FAIL: no command record $record"; exit 1; }
grep -q "shockgas-dump" "$record" || { echo "FAIL: $record does not hold the step's command"; cat "$record"; exit 1; }
if build_fig3 | grep -q "$step"; then echo "FAIL: the step reran with nothing changed"; exit 1; fi
original=$(cat "$record")
sleep 1  # a newer modification time than the step's outputs on any file system
echo "--an-option-edited-in-fig3.cmake" >>"$record"
build_fig3 | grep -q "$step" || { echo "FAIL: the step did not rerun after its command changed"; exit 1; }
cmake "$build" >/dev/null || { echo "FAIL: configuring $build"; exit 1; }
[ "$(cat "$record")" = "$original" ] || { echo "FAIL: configuring did not restore $record"; exit 1; }
build_fig3 | grep -q "$step" || { echo "FAIL: the step did not rerun after configuring restored its command"; exit 1; }
if build_fig3 | grep -q "$step"; then echo "FAIL: the step reran a second time with nothing changed"; exit 1; fi
echo "PASS: the step reruns when its command changes, and only then"
