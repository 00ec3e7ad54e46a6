#!/usr/bin/env bash
# faults_test.sh CASE SIM DIR [PYTHON COMPARE_OUTPUTS]
# One fault per CASE (docs/reliability.md); each says what must happen and fails otherwise.
#   file_size_output      a file-size limit (ulimit -f) during the output write: one line naming the
#                         file and "File too large", exit 2 (not killed by SIGXFSZ), nothing left behind
#   file_size_checkpoint  a resumed run whose next checkpoint exceeds the limit: one line naming the
#                         checkpoint, exit 2, both checkpoint generations untouched, no temporary file;
#                         a later --resume without the limit equals the uninterrupted run
#   stale_temporaries     *.tmp.<pid> of a dead process beside the output and the checkpoint are removed
#                         with a note; one of a live process is kept
#   lock                  a second --resume of a run in progress is refused with one line naming the
#                         holder; after the holder is killed with kill -9, a run on it works again
#                         (its checkpoint first refuses a run without --resume as an interrupted run)
#   resume_other_parameters  --resume with a checkpoint of a run with other parameters (-t 500 for -t 1000):
#                         refused before any work, exit 2, one line naming "t-max 500 vs 1000 in the
#                         checkpoint" and how to start anew; both generations kept; --resume with the
#                         right parameters then continues from them
#   rerun_without_resume  the interrupted run's command again without --resume (checkpoints on, or
#                         --checkpoint-interval 0): refused before any work, exit 2, one line giving how
#                         far the checkpoint got and when it was saved, --resume and how to start anew;
#                         both generations and the output kept. A damaged newest generation: refused
#                         naming the older one; both damaged: one warning each, the run starts from t = 0
#   memory_fewer_at_once  a --max-memory budget that fits one realization but not two: runs them one at
#                         a time, says so, and completes
#   resume_complete_output  --resume over this run's complete output (this build, no checkpoint): one
#                         line, exit 0, the file untouched and nothing run; an interrupted output, one of
#                         another build or with other parameters, or one beside a checkpoint is recomputed
#                         (or continued) as before; without --resume a rerun replaces it
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
case_name=$1 sim=$2 dir=$3 python=${4:-} same=${5:-}
source "$(dirname "$0")/checkpoint_helpers.sh"
# python/shockgas of this source tree reads outputs' attributes (resume_complete_output): on
# PYTHONPATH, set by ctest.
mkdir -p "$dir/$case_name"
cd "$dir/$case_name" || exit 1
rm -rf ./*
fail() { echo "FAIL [$case_name]: $*"; for f in ./*.err; do [ -e "$f" ] && { echo "--- $f"; cat "$f"; }; done; exit 1; }
# Lines of a stderr log other than the batch progress lines (stderr is not a
# terminal here, so shockgas-sim reports progress there too).
message_lines() { grep -vc '^shockgas-sim: progress:' "$1"; }

case $case_name in
file_size_output)
  # About 6 MB of snapshots (20000 particles x 32 bytes x 10 times) under a 2 MB limit.
  (ulimit -f 2048; exec "$sim" -N 20000 -r 0.9 -d 0.01 -t 10 -R 1 -q --checkpoint-interval 0 \
     --snapshot-interval 1 -o out.h5) 2>run.err
  status=$?
  [ "$status" -ne 0 ] || fail "exit status 0 under a file-size limit"
  [ "$status" -lt 128 ] || fail "killed by a signal (exit $status): SIGXFSZ must not end the process"
  [ "$(message_lines run.err)" -eq 1 ] || fail "expected one line on stderr"
  grep -q "^shockgas-sim: error: cannot write 'out.h5': File too large" run.err || fail "the line does not name the file and cause"
  [ ! -e out.h5 ] || fail "an output file was left"
  ls out.h5.tmp.* >/dev/null 2>&1 && fail "a temporary file was left"
  ;;
file_size_checkpoint)
  args=(-N 20000 -r 0.8 -d 0.005 -t 400 -R 2 -j 2 -q --seed 7 --snapshot-times 50,100)
  "$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || fail "reference run"
  # A checkpoint of the run in progress, from Ctrl-C.
  run_until_checkpoints 2 INT stopped.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o run.h5
  [ $? -eq 130 ] || fail "the run was not stopped mid-way: make it longer"
  cp run.h5.checkpoint saved.current
  cp run.h5.checkpoint.previous saved.previous
  size_kib=$(( $(stat -c %s run.h5.checkpoint) / 1024 ))
  # Resume under a limit of half the checkpoint's size: its next checkpoint cannot be written.
  (ulimit -f $((size_kib / 2)); exec "$sim" "${args[@]}" --checkpoint-interval 0.1 --resume -o run.h5) 2>limited.err
  status=$?
  [ "$status" -ne 0 ] || fail "exit status 0 although no checkpoint could be written"
  [ "$status" -lt 128 ] || fail "killed by a signal (exit $status)"
  [ "$(grep -c 'error' limited.err)" -eq 1 ] || fail "expected one error line"
  grep -q "^shockgas-sim: error: cannot write 'run.h5.checkpoint': File too large" limited.err ||
    fail "the error does not name the checkpoint and the cause"
  cmp -s saved.current run.h5.checkpoint && cmp -s saved.previous run.h5.checkpoint.previous ||
    fail "the previous checkpoints were changed"
  ls ./*.tmp.* >/dev/null 2>&1 && fail "a temporary file was left"
  [ ! -e run.h5 ] || [ "$(stat -c %s run.h5)" -gt 0 ] || fail "an empty output"
  "$sim" "${args[@]}" --checkpoint-interval 0 --resume -o run.h5 2>resumed.err || fail "the later --resume failed"
  grep -q "resuming from 'run.h5.checkpoint'" resumed.err || fail "the later --resume did not use the kept checkpoint"
  "$python" "$same" reference.h5 run.h5 || fail "the resumed run differs from the uninterrupted one"
  ;;
stale_temporaries)
  dead=999999999  # above any pid_max (at most 2^22): no such process
  : >out.h5.tmp.$dead
  : >out.h5.checkpoint.tmp.$((dead - 1))
  : >out.h5.tmp.$$  # this shell is alive: its file must stay
  "$sim" -N 100 -t 10 -q --checkpoint-interval 1 -o out.h5 2>run.err || fail "the run failed"
  grep -q "removed 'out.h5.tmp.$dead', left by a run that no longer exists" run.err || fail "no note for the stale output temporary"
  grep -q "removed 'out.h5.checkpoint.tmp.$((dead - 1))'" run.err || fail "no note for the stale checkpoint temporary"
  [ ! -e out.h5.tmp.$dead ] && [ ! -e out.h5.checkpoint.tmp.$((dead - 1)) ] || fail "stale temporaries left"
  [ -e out.h5.tmp.$$ ] || fail "the temporary file of a live process was removed"
  ;;
lock)
  args=(-N 100000 -r 0.9 -d 0.01 -t 1e6 -R 1 -q --seed 3)
  "$sim" "${args[@]}" --checkpoint-interval 0.2 --resume -o run.h5 2>first.err &
  first=$!
  trap 'kill -9 $first 2>/dev/null' EXIT
  for _ in $(seq 1 600); do
    grep -q '^shockgas-sim: checkpoint:' first.err && break
    sleep 0.02
  done
  kill -0 "$first" 2>/dev/null || fail "the first run ended too early"
  # Refused at once if the lock works; otherwise it would run on (stopped after 10 s).
  timeout 10 "$sim" "${args[@]}" --checkpoint-interval 0.2 --resume -o run.h5 2>second.err
  status=$?
  kill -0 "$first" 2>/dev/null || fail "the first run ended before the second was refused: make it longer"
  kill -9 "$first"
  wait "$first" 2>/dev/null
  [ "$status" -eq 2 ] || fail "the second --resume was not refused (exit $status)"
  [ "$(message_lines second.err)" -eq 1 ] || fail "expected one line from the refused run"
  grep -q "error: checkpoint 'run.h5.checkpoint' is in use by another running shockgas-sim (process $first)" second.err ||
    fail "the refusal does not name the checkpoint and the process holding it"
  # The lock dies with its holder, even with kill -9: its lock file is left, yet a run on the same
  # checkpoint is not refused for it. (The killed run's checkpoint refuses a run without --resume as
  # an interrupted run, and --resume would continue its t = 1e6: it is removed, as that refusal says,
  # and a short run starts anew beside the dead holder's lock file.)
  [ -e run.h5.checkpoint.lock ] || fail "kill -9 left no lock file: the test did not test"
  "$sim" -N 100000 -r 0.9 -d 0.01 -t 10 -R 1 -q --seed 3 -o run.h5 2>third.err
  grep -q "error: 'run.h5.checkpoint' holds an interrupted run" third.err ||
    fail "the dead holder's checkpoint was not refused as an interrupted run"
  rm -f run.h5.checkpoint run.h5.checkpoint.previous
  "$sim" -N 100000 -r 0.9 -d 0.01 -t 10 -R 1 -q --seed 3 -o run.h5 2>fourth.err ||
    fail "a run after the holder died was refused"
  ;;
resume_other_parameters)
  args=(-N 20000 -r 0.8 -d 0.005 -R 2 -j 2 -q -s 99)
  run_until_checkpoints 2 INT first.err -- "$sim" "${args[@]}" -t 1000 --checkpoint-interval 0.1 -o ck3.h5
  [ -e ck3.h5.checkpoint ] && [ -e ck3.h5.checkpoint.previous ] || fail "the interrupted run left no two generations"
  cp ck3.h5.checkpoint kept.checkpoint
  cp ck3.h5.checkpoint.previous kept.previous
  cp ck3.h5 kept.h5  # the interrupted output
  "$sim" "${args[@]}" -t 500 --checkpoint-interval 0.1 --resume -o ck3.h5 2>typo.err
  status=$?
  [ "$status" -eq 2 ] || fail "a checkpoint of another run was not refused (exit $status)"
  [ "$(wc -l <typo.err)" -eq 1 ] || fail "expected one line from the refused run"
  grep -q "^shockgas-sim: error: checkpoint 'ck3.h5.checkpoint' belongs to a run with other parameters: t-max 500 vs 1000 in the checkpoint;" typo.err ||
    fail "the refusal does not name the parameter that differs with both values"
  grep -q "to start anew, remove 'ck3.h5.checkpoint' and 'ck3.h5.checkpoint.previous', or choose another -o/--checkpoint" typo.err ||
    fail "the refusal does not say how to start anew"
  cmp -s kept.checkpoint ck3.h5.checkpoint && cmp -s kept.previous ck3.h5.checkpoint.previous ||
    fail "the refused run changed the checkpoints"
  cmp -s kept.h5 ck3.h5 || fail "the refused run wrote an output"
  # With --set-aside-other-runs (the figure pipeline's, whose parameter file says which run a path
  # holds) the other run's checkpoint is moved aside, untouched, and this run starts anew, so that
  # editing a stopped run's parameters does not fail the pipeline's build.
  cp kept.checkpoint sa.h5.checkpoint && cp kept.previous sa.h5.checkpoint.previous && cp kept.h5 sa.h5 ||
    fail "could not copy the checkpoints"
  "$sim" "${args[@]}" -t 500 --checkpoint-interval 0 -o reference500.h5 2>reference500.err || fail "the reference run failed"
  "$sim" "${args[@]}" -t 500 --checkpoint-interval 0 --resume --set-aside-other-runs -o sa.h5 2>set_aside.err ||
    fail "--resume --set-aside-other-runs over another run's checkpoint failed"
  grep -q "checkpoint 'sa.h5.checkpoint' belongs to a run with other parameters (t-max 500 vs 1000 in the checkpoint): moved aside to 'sa.h5.checkpoint.from-other-run' and 'sa.h5.checkpoint.from-other-run.previous'; this run does not continue it" set_aside.err ||
    fail "the run did not say that it moved the other run's checkpoint aside"
  cmp -s kept.checkpoint sa.h5.checkpoint.from-other-run && cmp -s kept.previous sa.h5.checkpoint.from-other-run.previous ||
    fail "the other run's checkpoint was not kept unchanged"
  [ ! -e sa.h5.checkpoint ] || fail "the finished run left a checkpoint"
  "$python" "$same" reference500.h5 sa.h5 >same.out 2>&1 || { cat same.out; fail "the run started anew differs from a fresh one"; }
  # Another simulator's checkpoint of another run is moved aside as another simulator's (no build
  # of this one continues it, whatever parameters are given), not refused: with and without the
  # flag (giving its parameters would not make this build continue it).
  for flag in "" --set-aside-other-runs; do
    cp kept.checkpoint os.h5.checkpoint && cp kept.previous os.h5.checkpoint.previous || fail "could not copy"
    rm -f os.h5.checkpoint.from-*
    "$python" -c "
import sys, h5py
for name in sys.argv[1:]:
    with h5py.File(name, 'r+') as f:
        f.attrs['version'] = 'oldbuild/1'
        del f.attrs['simulator_sha256']
" os.h5.checkpoint os.h5.checkpoint.previous || fail "could not mark the checkpoints as an older build's"
    "$sim" "${args[@]}" -t 50 --checkpoint-interval 0 --resume $flag -o os.h5 2>other_simulator.err ||
      { cat other_simulator.err; fail "another simulator's checkpoint of another run was refused ($flag)"; }
    grep -q "was written by shockgas oldbuild/1, this is .*, another simulator: starting from t = 0; kept it as 'os.h5.checkpoint.from-oldbuild_1'" other_simulator.err ||
      { cat other_simulator.err; fail "another simulator's checkpoint was not kept aside ($flag)"; }
  done
  # A running process's checkpoint is never moved aside: refused as its lock refuses it.
  "$sim" "${args[@]}" -t 1000000 --checkpoint-interval 0.1 -o busy.h5 2>busy.err &
  busy=$!
  for _ in $(seq 1 600); do [ -e busy.h5.checkpoint ] && break; sleep 0.02; done
  [ -e busy.h5.checkpoint ] || { kill -INT "$busy"; wait "$busy"; fail "the running run wrote no checkpoint"; }
  "$sim" "${args[@]}" -t 50 --checkpoint-interval 0 --resume --set-aside-other-runs -o busy.h5 2>busy_aside.err
  status=$?
  kill -INT "$busy"; wait "$busy"
  [ "$status" -eq 2 ] || fail "setting aside a running process's checkpoint was not refused (exit $status)"
  grep -q "in use by another running shockgas-sim" busy_aside.err || { cat busy_aside.err; fail "the refusal does not name the lock"; }
  ! ls busy.h5.checkpoint.from-* >/dev/null 2>&1 || fail "a running process's checkpoint was moved aside"
  "$sim" "${args[@]}" -t 1000 --checkpoint-interval 0 --resume -o ck3.h5 2>resumed.err || fail "the right --resume failed"
  grep -q "resuming from 'ck3.h5.checkpoint'" resumed.err || fail "the right --resume did not use the checkpoint"
  ;;
hangup)
  # SIGHUP (a closed terminal, a dropped ssh session) stops a run as SIGINT does: exit 130, the
  # interrupted output and a checkpoint, from which --resume gives the uninterrupted result.
  args=(-N 20000 -r 0.8 -d 0.005 -R 2 -j 2 -q -s 99 -t 1000)
  "$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || fail "the reference run failed"
  run_until_checkpoints 2 HUP first.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o hup.h5
  status=$?
  [ "$status" -eq 130 ] || fail "SIGHUP did not stop the run as an interruption (exit $status)"
  grep -q "^shockgas-sim: interrupted" first.err || fail "no interrupted output after SIGHUP"
  [ -e hup.h5.checkpoint ] || fail "no checkpoint after SIGHUP"
  "$sim" "${args[@]}" --checkpoint-interval 0 --resume -o hup.h5 2>resumed.err || fail "the --resume after SIGHUP failed"
  "$python" "$same" reference.h5 hup.h5 >same.out 2>&1 || { cat same.out; fail "the resumed run differs from the uninterrupted one"; }
  ;;
resume_other_build)
  # A checkpoint written by a build of another simulator (another simulator_sha256): the run starts
  # anew (no other simulator continues a run bit for bit), and both generations are moved aside,
  # untouched, for a build of the simulator that wrote them.
  args=(-N 20000 -r 0.8 -d 0.005 -R 2 -j 2 -q -s 99 -t 1000)
  "$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || fail "the reference run failed"
  run_until_checkpoints 2 INT first.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o ob.h5
  [ -e ob.h5.checkpoint ] && [ -e ob.h5.checkpoint.previous ] || fail "the interrupted run left no two generations"
  "$python" -c "
import sys, h5py
for name in sys.argv[1:]:
    with h5py.File(name, 'r+') as f:
        f.attrs['version'] = 'oldbuild/1'
        f.attrs['simulator_sha256'] = '0' * 64
" ob.h5.checkpoint ob.h5.checkpoint.previous || fail "could not mark the checkpoints as another build's"
  cp ob.h5.checkpoint kept.checkpoint
  cp ob.h5.checkpoint.previous kept.previous
  "$sim" "${args[@]}" --checkpoint-interval 0.1 --resume -o ob.h5 2>resumed.err || fail "the --resume failed"
  grep -q "checkpoint 'ob.h5.checkpoint' was written by shockgas oldbuild/1 (simulator 000000000000), this is shockgas .* (simulator [0-9a-f]\{12\}), another simulator: starting from t = 0; kept it as 'ob.h5.checkpoint.from-oldbuild_1-00000000' and 'ob.h5.checkpoint.from-oldbuild_1-00000000.previous'" resumed.err ||
    fail "the run did not say where it kept the other build's checkpoint"
  cmp -s kept.checkpoint ob.h5.checkpoint.from-oldbuild_1-00000000 &&
    cmp -s kept.previous ob.h5.checkpoint.from-oldbuild_1-00000000.previous ||
    fail "the other build's checkpoint was not kept unchanged"
  [ ! -e ob.h5.checkpoint ] || fail "the finished run left its own checkpoint"
  "$python" "$same" reference.h5 ob.h5 >same.out 2>&1 || { cat same.out; fail "the run started anew differs from the uninterrupted one"; }
  ;;
resume_same_simulator)
  # A checkpoint written by another version of the same simulator (a commit that changed only docs,
  # analysis or tests, or an uncommitted edit there: the same simulator_sha256) is continued: the
  # result is bit-identical to an uninterrupted run, so that a docs commit between `paper-tier stop`
  # and `start` does not throw away the runs in progress.
  args=(-N 20000 -r 0.8 -d 0.005 -R 2 -j 2 -q -s 99 -t 1000)
  "$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || fail "the reference run failed"
  run_until_checkpoints 2 INT first.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o ss.h5
  [ -e ss.h5.checkpoint ] || fail "the interrupted run left no checkpoint"
  "$python" -c "
import sys, h5py
for name in sys.argv[1:]:
    with h5py.File(name, 'r+') as f:
        assert len(f.attrs['simulator_sha256']) == 64, 'no simulator_sha256 in the checkpoint'
        f.attrs['version'] = 'docsonly/1'
" ss.h5.checkpoint ss.h5.checkpoint.previous || fail "could not mark the checkpoints as another version's"
  "$sim" "${args[@]}" --checkpoint-interval 0 --resume -o ss.h5 2>resumed.err || fail "the --resume failed"
  grep -q "checkpoint 'ss.h5.checkpoint' was written by shockgas docsonly/1 (simulator [0-9a-f]\{12\}), this is .*: the same simulator (sources, compiler and flags), so it is continued" resumed.err ||
    { cat resumed.err; fail "the run did not say that it continued another version's checkpoint"; }
  grep -q "resuming from 'ss.h5.checkpoint'" resumed.err || { cat resumed.err; fail "the run did not resume"; }
  ! ls ss.h5.checkpoint.from-* >/dev/null 2>&1 || fail "the same simulator's checkpoint was moved aside"
  "$python" "$same" reference.h5 ss.h5 >same.out 2>&1 || { cat same.out; fail "the resumed run differs from the uninterrupted one"; }
  ;;
rerun_without_resume)
  args=(-N 20000 -r 0.8 -d 0.005 -R 2 -j 2 -q -s 99 -t 1000)
  run_until_checkpoints 2 INT first.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o rr.h5
  [ -e rr.h5.checkpoint ] && [ -e rr.h5.checkpoint.previous ] || fail "the interrupted run left no two generations"
  cp rr.h5.checkpoint kept.checkpoint
  cp rr.h5.checkpoint.previous kept.previous
  cp rr.h5 kept.h5  # the interrupted output
  saved='saved [0-9]{4}-[0-9]{2}-[0-9]{2} [0-9]{2}:[0-9]{2} UTC'
  progress='[0-2] of 2 realizations done(, the furthest at t = [0-9.e+]+ of 1000)?'
  # The same command without --resume, with checkpoints (it would overwrite both generations and
  # remove them at its end) and without (it would redo the hours the checkpoint holds).
  for interval in 0.1 0; do
    timeout 100 "$sim" "${args[@]}" --checkpoint-interval $interval -o rr.h5 2>again$interval.err
    status=$?
    [ "$status" -eq 2 ] ||
      fail "a rerun without --resume (--checkpoint-interval $interval) over an interrupted run's checkpoint was not refused (exit $status)"
    [ "$(wc -l <again$interval.err)" -eq 1 ] || fail "expected one line from the refused run"
    grep -Eq "^shockgas-sim: error: 'rr\.h5\.checkpoint' holds an interrupted run \($progress, $saved\): continue it with --resume, or remove 'rr\.h5\.checkpoint' and 'rr\.h5\.checkpoint\.previous' to start anew$" again$interval.err ||
      fail "the refusal does not say what the checkpoint holds, --resume and how to start anew"
    cmp -s kept.checkpoint rr.h5.checkpoint && cmp -s kept.previous rr.h5.checkpoint.previous ||
      fail "the refused run changed the checkpoints"
    cmp -s kept.h5 rr.h5 || fail "the refused run wrote an output"
  done
  # A damaged newest generation: the older one still holds the run.
  truncate -s $(( $(stat -c %s rr.h5.checkpoint) / 2 )) rr.h5.checkpoint
  "$sim" "${args[@]}" --checkpoint-interval 0.1 -o rr.h5 2>damaged.err
  status=$?
  [ "$status" -eq 2 ] || fail "the older generation of a damaged checkpoint was not protected (exit $status)"
  [ "$(wc -l <damaged.err)" -eq 1 ] || fail "expected one line from the refused run"
  grep -Eq "^shockgas-sim: error: 'rr\.h5\.checkpoint\.previous' holds an interrupted run \($progress, $saved\): continue it with --resume, or remove 'rr\.h5\.checkpoint' and 'rr\.h5\.checkpoint\.previous' to start anew$" damaged.err ||
    fail "the refusal does not name the older generation"
  cmp -s kept.previous rr.h5.checkpoint.previous || fail "the refused run changed the older generation"
  # Both damaged: nothing can be continued (as --resume would say), so the run starts, saying so.
  truncate -s $(( $(stat -c %s rr.h5.checkpoint.previous) / 2 )) rr.h5.checkpoint.previous
  "$sim" -N 2000 -r 0.8 -d 0.005 -R 1 -q -s 99 -t 50 --checkpoint-interval 0.1 -o rr.h5 2>both.err ||
    fail "a run over two damaged checkpoint generations failed"
  [ "$(grep -c "^shockgas-sim: warning: .*'rr\.h5\.checkpoint\(\.previous\)\?' .*; it cannot be continued: starting from t = 0$" both.err)" -eq 2 ] ||
    fail "expected one warning per damaged generation"
  [ ! -e rr.h5.checkpoint ] && [ ! -e rr.h5.checkpoint.previous ] || fail "the finished run left checkpoints"
  ;;
memory_fewer_at_once)
  # 100000 particles: about 25 MiB per running realization with checkpoints (docs/reliability.md); 60 MiB
  # holds the program and one, not two.
  "$sim" -N 100000 -r 0.9 -d 0.01 -t 10 -R 2 -j 2 -q --max-memory 60M -o out.h5 2>run.err || fail "the run failed"
  grep -q "running realizations 1 at a time instead of 2" run.err || fail "no note that fewer realizations run at once"
  grep -q "complete" run.err || fail "the run did not complete"
  ;;
resume_complete_output)
  args=(-N 2000 -r 0.8 -d 0.005 -R 2 -j 2 -s 99 -t 100)
  nothing="^shockgas-sim: 'done\.h5' is already a complete output of this run; nothing to do \(remove it, or run without --resume, to recompute\)$"
  "$sim" "${args[@]}" -q --checkpoint-interval 0 -o done.h5 2>first.err || fail "the first run failed"
  cp done.h5 kept.h5
  for interval in 0 0.1; do
    "$sim" "${args[@]}" --checkpoint-interval $interval --resume -o done.h5 >again$interval.out 2>again$interval.err ||
      fail "--resume over the complete output failed (--checkpoint-interval $interval)"
    [ "$(wc -l <again$interval.err)" -eq 1 ] && grep -Eq "$nothing" again$interval.err ||
      fail "--resume over the complete output did not say, in one line, that there is nothing to do"
    [ ! -s again$interval.out ] || fail "--resume over the complete output printed a table: it ran"
    cmp -s kept.h5 done.h5 || fail "--resume over the complete output rewrote it"
    ls done.h5.checkpoint* >/dev/null 2>&1 && fail "--resume over the complete output left a checkpoint"
  done
  # Recomputed as before: each is marked so that a rewrite shows (its date attribute is the run's).
  set_attribute() {
    "$python" -c "
import sys, h5py
with h5py.File(sys.argv[1], 'r+') as f:
    f.attrs[sys.argv[2]] = sys.argv[3]
" done.h5 "$1" "$2" || fail "could not set $1 of done.h5"
  }
  recomputed() {  # recomputed WHY ARGS...: --resume ARGS over done.h5 runs and writes a complete output
    "$sim" "${@:2}" -q --checkpoint-interval 0 --resume -o done.h5 2>"$1.err" || fail "--resume ($1) failed"
    grep -q "nothing to do" "$1.err" && fail "--resume ($1) was taken for nothing to do"
    grep -q "^shockgas-sim: complete" "$1.err" || fail "--resume ($1) did not run to a complete output"
    "$python" -c "
import sys, shockgas
a = shockgas.attributes(sys.argv[1])
sys.exit(0 if a['date'] != 'marked' and a['status'] == 'complete' else 1)
" done.h5 || fail "--resume ($1) did not replace the output"
  }
  set_attribute status interrupted; set_attribute date marked
  recomputed interrupted "${args[@]}"
  # Another version of the same simulator (the same simulator_sha256) made the same numbers: nothing to do.
  set_attribute version docsonly/1
  cp done.h5 kept.h5
  "$sim" "${args[@]}" --checkpoint-interval 0 --resume -o done.h5 2>same_simulator.err ||
    fail "--resume over the same simulator's complete output failed"
  grep -Eq "$nothing" same_simulator.err && cmp -s kept.h5 done.h5 ||
    fail "--resume over another version's output of the same simulator recomputed it"
  set_attribute simulator_sha256 0000000000000000000000000000000000000000000000000000000000000000
  set_attribute date marked
  recomputed other_build "${args[@]}"
  set_attribute date marked
  recomputed other_parameters -N 2000 -r 0.8 -d 0.005 -R 2 -j 2 -s 99 -t 50
  "$sim" "${args[@]}" -q --checkpoint-interval 0 -o done.h5 2>restore.err || fail "a rerun without --resume failed"
  # A checkpoint beside it (here one too damaged to read: --resume passes over it with a warning).
  set_attribute date marked
  : >done.h5.checkpoint
  recomputed beside_checkpoint "${args[@]}"
  grep -q "warning: .*done\.h5\.checkpoint" beside_checkpoint.err || fail "the damaged checkpoint was not looked at"
  # Without --resume, a rerun replaces the complete output, as before.
  set_attribute date marked
  "$sim" "${args[@]}" -q --checkpoint-interval 0 -o done.h5 2>rerun.err || fail "a rerun without --resume failed"
  grep -q "nothing to do" rerun.err && fail "a rerun without --resume was taken for nothing to do"
  "$python" -c "
import sys, shockgas
sys.exit(0 if shockgas.attributes(sys.argv[1])['date'] != 'marked' else 1)
" done.h5 || fail "a rerun without --resume did not replace the output"
  ;;
*) echo "unknown case $case_name"; exit 1 ;;
esac
echo "ok [$case_name]"
