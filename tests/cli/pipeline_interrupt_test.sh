#!/usr/bin/env bash
# pipeline_interrupt_test.sh BUILD_DIR TARGET RUN_H5 PYTHON
# A figure build stopped while one of its simulations runs (SIGTERM to the
# build's process group, as scancel or a closed terminal sends) must not leave
# that run's output in place: shockgas-sim still writes its file, marked
# "interrupted", and were it the rule's output make would take it as done and
# feed a partial run to the analysis. The pipeline stages each run as
# <name>.running.h5 and renames it only after shockgas-sim exits 0.
#   1. delete RUN_H5 and build TARGET; once that run's shockgas-sim is running,
#      SIGTERM the whole build;
#   2. the build must fail, RUN_H5 must not exist, and the staged file must
#      say "interrupted";
#   3. build TARGET again: it must resume from the staged run's checkpoint,
#      succeed, and leave RUN_H5 with status "complete".
# It fails, rather than passing vacuously, if the run ends before it is stopped.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
build=$1 target=$2 out=$3 python=$4
staged="${out%.h5}.running.h5"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# python/shockgas of this source tree reads the file's status: on PYTHONPATH, set by ctest.
status_of() { "$python" -c 'import shockgas, sys; print(shockgas.attributes(sys.argv[1])["status"])' "$1"; }

running="--output ${out%.h5}"  # the run's shockgas-sim, whatever name it writes
rm -f "$out" "$staged" "$staged.checkpoint" "$out.checkpoint"
setsid cmake --build "$build" --target "$target" >"$log" 2>&1 &
build_pid=$!
for _ in $(seq 1 1200); do
  pgrep -f -- "$running" >/dev/null && break
  kill -0 "$build_pid" 2>/dev/null || break
  sleep 0.1
done
pgrep -f -- "$running" >/dev/null || { cat "$log"; echo "FAIL: the run of $out never started"; exit 1; }
sleep 2  # into the run, past its first events
pgrep -f -- "$running" >/dev/null || { echo "FAIL: the run ended before it could be stopped: make it longer"; exit 1; }
kill -TERM -- "-$build_pid"
wait "$build_pid"
code=$?
# make may exit before shockgas-sim has written its interrupted file: wait for it.
for _ in $(seq 1 600); do pgrep -f -- "$running" >/dev/null || break; sleep 0.1; done
tail -3 "$log"
[ "$code" -ne 0 ] || { echo "FAIL: the stopped build exited 0"; exit 1; }
[ -e "$out" ] && { echo "FAIL: $out exists after the build was stopped (status: $(status_of "$out"))"; exit 1; }
[ "$(status_of "$staged")" = interrupted ] || { echo "FAIL: the staged file is not marked interrupted"; exit 1; }

cmake --build "$build" --target "$target" >"$log" 2>&1 || { cat "$log"; echo "FAIL: the second build"; exit 1; }
grep -q "resuming from '$staged.checkpoint'" "$log" || { cat "$log"; echo "FAIL: the second build did not resume"; exit 1; }
[ "$(status_of "$out")" = complete ] || { echo "FAIL: $out is not complete after the second build"; exit 1; }
[ -e "$staged" ] && { echo "FAIL: the staged file was left behind"; exit 1; }
echo "ok: stopped build left no $out; the rebuild resumed and completed it"
