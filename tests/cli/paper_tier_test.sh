#!/usr/bin/env bash
# paper_tier_test.sh TOOL SIM WORK_DIR: tools/paper-tier on a throwaway CMake project whose targets
# stand in for the pipeline's: `quick` touches a file, `simulate` runs shockgas-sim long enough to be
# stopped. Asserts that start runs a target in the background and records its end with rc = 0; that a
# second start while one runs starts nothing (and, asked for another target, says in one line with exit 2
# that it was not added and how to add it, but asked for a target the running one builds, such as fig1
# while `figures` runs, that there is nothing to do, exit 0); that every hint start and stop print names the --build DIR
# given; that stop ends every process of the build and the simulation writes its last checkpoint on the
# way (so a later start resumes it); and that paper-tier.times records each start and end; and that
# --jobs 2 runs two targets at once (two that each wait for the other to start, so that one at a time
# times out).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
tool=$1 sim=$2 work=$3
fail() {
  echo "FAIL: $*"
  [ -f "$work/build/paper-tier.log" ] && tail -n 20 "$work/build/paper-tier.log"
  "$tool" stop --build "$work/build" >/dev/null 2>&1  # leave nothing running
  exit 1
}
rm -rf "$work" && mkdir -p "$work/project" || exit 1
cat >"$work/project/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.20)
project(paper_tier_test NONE)
add_custom_target(quick COMMAND ${CMAKE_COMMAND} -E touch ${CMAKE_BINARY_DIR}/quick.done)
# Each of these starts, then waits up to 120 s for the other to start: both finish only side by side.
# (The tool builds at the lowest priority, so on a loaded machine a target can wait long for a core.)
add_custom_target(side_a COMMAND sh ${CMAKE_SOURCE_DIR}/meet.sh ${CMAKE_BINARY_DIR} a b)
add_custom_target(side_b COMMAND sh ${CMAKE_SOURCE_DIR}/meet.sh ${CMAKE_BINARY_DIR} b a)
add_custom_target(side_by_side DEPENDS side_a side_b)
# The pipeline's `figures` builds fig1 (and the other figure targets): here fig1 runs until told to end
# (the file release appears), for up to 300 s.
add_custom_target(fig1 COMMAND sh -c "touch fig1.started; i=0; while [ ! -f release ] && [ $i -lt 3000 ]; do i=$((i + 1)); sleep 0.1; done"
                  WORKING_DIRECTORY ${CMAKE_BINARY_DIR} VERBATIM)
add_custom_target(figures)
add_dependencies(figures fig1)
# Long enough (N = 20000 to t = 1e6 with the event engine: minutes) to be stopped while it runs.
add_custom_target(simulate COMMAND ${SIM} -N 20000 -t 1e6 -R 1 -q --resume --checkpoint-interval 3600
                  --output ${CMAKE_BINARY_DIR}/run.h5)
EOF
cat >"$work/project/meet.sh" <<'EOF'
touch "$1/$2.started"
i=0
while [ ! -f "$1/$3.started" ]; do
  i=$((i + 1)); [ $i -le 1200 ] || { echo "$2 waited 120 s for $3"; exit 1; }
  sleep 0.1
done
touch "$1/$2.met"
EOF
cmake -S "$work/project" -B "$work/build" -DSIM="$sim" >/dev/null || fail "the test project did not configure"
build=$work/build
# Up to 300 s of wall time: the builds run at the lowest priority, so under other load (a CI run beside
# simulations: a load of 10 on 2 cores) they take far longer than the seconds they need idle.
stop_wait=300
wait_until_stopped() {
  local deadline=$((SECONDS + stop_wait))
  while ((SECONDS < deadline)); do
    "$tool" status --build "$build" | grep -q "^paper-tier: not running" && return 0
    sleep 0.1
  done
  return 1
}

started=$("$tool" start --build "$build" quick) || fail "start failed"
# Every hint names the --build DIR given (without it, 'paper-tier stop' would look in the default
# build-paper, say "not running" with exit 0, and the build would go on).
echo "$started" | grep -qF "'paper-tier stop --build $build' stops it" || fail "start's stop hint lacks --build: $started"
echo "$started" | grep -qF "'paper-tier status --build $build' shows" || fail "start's status hint lacks --build: $started"
# The start is on record when start returns (not later, from the background), so that a second start
# or a status right after it sees it.
[ "$(grep -c '^start' "$build/paper-tier.times" 2>/dev/null)" = 1 ] || fail "start returned before its start was recorded"
wait_until_stopped || fail "the quick target still runs after $stop_wait s"
[ -f "$build/quick.done" ] || fail "the quick target did not run"
tail -n 1 "$build/paper-tier.times" | grep -q '^end .* rc=0$' || fail "no end with rc=0: $(cat "$build/paper-tier.times")"

"$tool" start --build "$build" --jobs 2 side_by_side >/dev/null || fail "start with --jobs 2 failed"
tail -n 1 "$build/paper-tier.times" | grep -q ' jobs 2$' || fail "the start did not record its jobs: $(tail -n 1 "$build/paper-tier.times")"
wait_until_stopped || fail "the two side-by-side targets still run after $stop_wait s"
[ -f "$build/a.met" ] && [ -f "$build/b.met" ] || fail "--jobs 2 did not run two targets at once"
tail -n 1 "$build/paper-tier.times" | grep -q '^end .* rc=0$' || fail "side by side: no end with rc=0"
bad_jobs=$("$tool" start --build "$build" --jobs 0 quick 2>&1) && fail "--jobs 0 was accepted"
echo "$bad_jobs" | grep -q "at least 1" || fail "--jobs 0: $bad_jobs"

# While `figures` runs, a start of fig1, which it builds, is nothing to do (exit 0), not "fig1 NOT
# added", exit 2, as comparing the names alone would say. A target it does not build is still refused.
"$tool" start --build "$build" figures >/dev/null || fail "start of figures failed"
for ((i = 0; i < 3000; ++i)); do
  [ -f "$build/fig1.started" ] && break
  sleep 0.1
done
[ -f "$build/fig1.started" ] || fail "figures did not start fig1"
covered=$("$tool" start --build "$build" fig1 2>&1)
status=$?
[ $status = 0 ] || fail "start fig1 while figures runs: exit $status, expected 0: $covered"
echo "$covered" | grep -q "already running in '$build' .* with figures" || fail "start fig1 while figures runs: $covered"
uncovered=$("$tool" start --build "$build" fig1 quick 2>&1 >/dev/null)
status=$?
[ $status = 2 ] || fail "start of a target figures does not build: exit $status, expected 2: $uncovered"
case $uncovered in
  *" with figures: quick NOT added; "*) ;;
  *) fail "start fig1 quick while figures runs: $uncovered" ;;
esac
touch "$build/release"
wait_until_stopped || fail "figures still runs after $stop_wait s"
tail -n 1 "$build/paper-tier.times" | grep -q '^end .* rc=0$' || fail "figures: no end with rc=0"

own_autogroup=$(cat /proc/$$/autogroup 2>/dev/null)
"$tool" start --build "$build" simulate || fail "start of the simulation failed"
status=$("$tool" status --build "$build")
echo "$status" | grep -q "^paper-tier: running" || fail "status does not say it runs: $status"
pid=$(cat "$build/paper-tier.pid")
# The build's own session yields (autogroup nice 19, where the kernel groups sessions); the caller's
# does not change.
[ "$(cat /proc/$$/autogroup 2>/dev/null)" = "$own_autogroup" ] || fail "start changed the caller's autogroup"
if [ "$(cat /proc/sys/kernel/sched_autogroup_enabled 2>/dev/null)" = 1 ]; then
  for ((i = 0; i < 100; ++i)); do
    grep -q "nice 19" "/proc/$pid/autogroup" 2>/dev/null && break
    sleep 0.05
  done
  grep -q "nice 19" "/proc/$pid/autogroup" || fail "the build's autogroup: $(cat "/proc/$pid/autogroup")"
fi
again=$("$tool" start --build "$build" simulate)
echo "$again" | grep -q "already running" || fail "a second start did not see the first: $again"
echo "$again" | grep -qF "'paper-tier status --build $build'" || fail "the second start's hint lacks --build: $again"
# A start with other targets while one runs builds none of them: one line saying so and how to add
# them, exit 2 (not "already running", exit 0, with the new targets silently not built).
other=$("$tool" start --build "$build" quick simulate 2>&1 >/dev/null)
status=$?
[ $status = 2 ] || fail "a start with other targets while one runs: exit $status, expected 2: $other"
[ "$(echo "$other" | wc -l)" = 1 ] || fail "more than one line: $other"
case $other in
  "paper-tier: error: already running in '$build' "*" with simulate: quick NOT added; "*"'paper-tier stop --build $build', then 'paper-tier start --build $build simulate quick'"*) ;;
  *) fail "a start with other targets while one runs: $other" ;;
esac
[ "$(grep -c '^start' "$build/paper-tier.times")" = 4 ] || fail "a second start was recorded"
# Wait until the simulation itself runs, then stop the whole build.
for ((i = 0; i < 3000; ++i)); do
  pgrep -g "$pid" -f "run.h5" >/dev/null && break
  sleep 0.1
done
pgrep -g "$pid" -f "run.h5" >/dev/null || fail "the simulation did not start"
# Stop it only once it catches SIGTERM (signal 15: bit 14 of SigCgt): its handler writes the last checkpoint, and a
# signal before the handler is installed ends it with nothing to save. Under a sanitizer on a loaded
# computer the start can take longer than a second (then the test would fail with "left no checkpoint").
sim_pid=$(pgrep -g "$pid" -x shockgas-sim | head -n 1)
[ -n "$sim_pid" ] || fail "no shockgas-sim process in the build's group"
for ((i = 0; i < 600; ++i)); do
  mask=$(awk '/^SigCgt:/ {print $2}' "/proc/$sim_pid/status" 2>/dev/null)
  [ -n "$mask" ] && (( (16#$mask >> 14) & 1 )) && break
  sleep 0.1
done
sleep 1
stopped=$("$tool" stop --build "$build") || fail "stop failed"
echo "$stopped" | grep -qF "'paper-tier start --build $build simulate' continues it" || fail "stop's hint lacks --build or the targets: $stopped"
pgrep -g "$pid" >/dev/null && fail "processes of the build are left: $(pgrep -a -g "$pid")"
[ -f "$build/run.h5.checkpoint" ] || fail "the stopped simulation left no checkpoint"
tail -n 1 "$build/paper-tier.times" | grep -q '^end .* rc=[1-9]' || fail "the stop was not recorded as a failed end"
"$tool" status --build "$build" | grep -q "^paper-tier: not running" || fail "status after stop"
# A second start continues the simulation from that checkpoint.
"$tool" start --build "$build" simulate >/dev/null || fail "the second start failed"
for ((i = 0; i < 3000; ++i)); do
  grep -q "resuming from '$build/run.h5.checkpoint'" "$build/paper-tier.log" && break
  sleep 0.1
done
grep -q "resuming from '$build/run.h5.checkpoint'" "$build/paper-tier.log" || fail "the second start did not resume"
"$tool" stop --build "$build" >/dev/null || fail "the second stop failed"
[ "$(grep -c '^end .* rc=[1-9]' "$build/paper-tier.times")" = 2 ] || fail "the second stop was not recorded"
stop_again=$("$tool" stop --build "$build")
echo "$stop_again" | grep -q "not running" || fail "stop of a stopped build: $stop_again"
# A pid file left by a build that ended without recording it (a reboot, a kill -9) may name a process
# that is not the build: status must not claim it, stop must not signal it, start must not refuse.
setsid sleep 300 </dev/null >/dev/null 2>&1 &
stranger=$!
echo "$stranger" >"$build/paper-tier.pid"
"$tool" status --build "$build" | grep -q "^paper-tier: not running" || fail "status took a stranger for the build"
"$tool" stop --build "$build" >/dev/null
kill -0 "$stranger" 2>/dev/null || fail "stop signalled a process that was not the build"
kill "$stranger"
echo "ok"
