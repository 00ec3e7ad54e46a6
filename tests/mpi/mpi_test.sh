#!/usr/bin/env bash
# mpi_test.sh CASE SIM FAILING_RUN PYTHON WORK_DIR MPIEXEC...: end-to-end tests of
# `mpirun -np 2 shockgas-sim` (tests/mpi/CMakeLists.txt registers them).
#   identical     5 realizations over 2 ranks (3 + 2, uneven on purpose) give
#                 the datasets of a single-process run, bit for bit
#   idle_rank     1 realization over 2 ranks: rank 1 idles, same file again
#   failing_rank  a rank that fails before or after its run makes the job
#                 fail with a line naming it, no output file, and no hang
#   interrupted   Ctrl-C on mpirun (which sends SIGTERM to every rank) still
#                 gives one file, written by rank 0, marked interrupted
#   failing_run   a rank that fails during its run stops the whole job at once
#                 (FAILING_RUN, tests/mpi/failing_run.cpp)
#   other_ranks   a run interrupted in one process resumes on 2 ranks, and one
#                 interrupted on 2 ranks resumes in one process: each block's
#                 realizations are gathered from the other blocks' checkpoints,
#                 the file equals an uninterrupted run's bit for bit, and no
#                 checkpoint is left behind
#   finished_rank  Ctrl-C after rank 1 has finished its block but before rank 0
#                 has: rank 1 keeps a checkpoint of its finished block, --resume
#                 takes its realization from it instead of running it again, and
#                 the file equals an uninterrupted run's bit for bit
#   complete_output  --resume on 2 ranks over the run's complete output: rank 0
#                 finds nothing to do, every rank leaves, exit 0, one line, the
#                 file untouched
# MPIEXEC... is the launcher and its process-count flag, e.g. "mpiexec -n".
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
case_name=$1 sim=$2 failing_run=$3 python=$4 work=$5
shift 5
mpiexec=("$@")
here=$(cd "$(dirname "$0")" && pwd)
compare="$here/../compare_outputs.py"  # shared with the checkpoint tests
ranks=2

# The run of the task: N = 2000, r = 0.9, delta = 1e-2 to t = 100, with
# snapshots and histograms so that every dataset kind is compared.
physics=(-N 2000 -r 0.9 -d 1e-2 -t 100 --snapshot-times 10,100 --histogram-times 10,100 -q)

program=$sim
# shellcheck source=mpi_common.sh
. "$here/mpi_common.sh"
enter_work_folder "$work"

case "$case_name" in
identical)
  check_identical 5
  ;;
idle_rank)
  check_idle_rank
  ;;
failing_rank)
  # Rank 1's parameter out of range; its message must reach the job's stderr.
  check_failing_rank "samples per decade must lie in" --samples-per-decade 0
  ;;
interrupted)
  # A run far too long to finish; the signal comes once every rank has had
  # ample time to install its handler (start-up takes about 0.5 s).
  startup_seconds=5
  "${mpiexec[@]}" "$ranks" "$sim" -N 200000 -r 0.9 -d 1e-2 -t 1e6 -R 3 -j 1 -q -o interrupted.h5 \
    2>interrupted.stderr &
  launcher=$!
  sleep "$startup_seconds"
  kill -INT "$launcher"
  wait "$launcher" && fail "the interrupted job reported success"
  cat interrupted.stderr
  [ -s interrupted.h5 ] || fail "no output file after the interrupt"
  status=$("$python" -c 'import shockgas, sys; print(shockgas.attributes(sys.argv[1])["status"])' interrupted.h5)
  [ "$status" = interrupted ] || fail "the file's status is '$status', not interrupted"
  ;;
failing_run)
  # Rank 0 would run for 10 minutes; rank 1's failure must end the job now.
  max_seconds=30
  start=$SECONDS
  if "${mpiexec[@]}" "$ranks" "$failing_run" 2>run.stderr; then fail "the job succeeded although rank 1 failed"; fi
  cat run.stderr
  grep -q "simulated failure during the run of rank 1" run.stderr || fail "rank 1's error is missing"
  [ $((SECONDS - start)) -lt "$max_seconds" ] || fail "the job took $((SECONDS - start)) s to stop after rank 1 failed"
  ;;
other_ranks)
  # Long enough (6 realizations of about 1.3 s each) for an interrupt after
  # 2.5 s to leave realizations finished, in progress and not started; the
  # hybrid engine, so that states from both of its phases are carried over.
  run=(-N 20000 -r 0.9 -d 1e-2 --subthreshold elastic --engine hybrid -t 3000 --snapshot-times 100
       --histogram-times 100,3000 -R 6 -s 7 -j 1 -q)
  interrupt_after=2.5
  "$sim" "${run[@]}" -o reference.h5 || fail "the uninterrupted run failed"
  # One process, interrupted; two ranks continue it.
  "$sim" "${run[@]}" --checkpoint-interval 0.3 -o one_then_two.h5 2>one.stderr &
  pid=$!
  sleep "$interrupt_after"
  kill -INT "$pid"
  wait "$pid" && fail "the run finished before the interrupt: the test did not test"
  [ -e one_then_two.h5.checkpoint ] || fail "no checkpoint after the interrupt: $(cat one.stderr)"
  "${mpiexec[@]}" "$ranks" "$sim" "${run[@]}" --resume -o one_then_two.h5 2>two.stderr ||
    fail "mpirun -np $ranks --resume failed: $(cat two.stderr)"
  cat two.stderr
  grep -q "rank 0\]: gathering [1-9]" two.stderr || fail "rank 0 did not gather from the one-process checkpoint"
  "$python" "$compare" reference.h5 one_then_two.h5 "$ranks" ||
    fail "one process then $ranks ranks differs from the uninterrupted run"
  left=$(ls one_then_two.h5.checkpoint* 2>/dev/null)
  [ -z "$left" ] || fail "checkpoints left behind: $left"
  # Two ranks, interrupted; one process continues.
  "${mpiexec[@]}" "$ranks" "$sim" "${run[@]}" --checkpoint-interval 0.3 -o two_then_one.h5 2>two_first.stderr &
  launcher=$!
  sleep "$interrupt_after"
  kill -INT "$launcher"
  wait "$launcher" && fail "the $ranks-rank run finished before the interrupt: the test did not test"
  for k in 0 1; do
    [ -e two_then_one.h5.checkpoint.rank$k ] || fail "no checkpoint of rank $k: $(cat two_first.stderr)"
  done
  "$sim" "${run[@]}" --resume -o two_then_one.h5 2>one_after.stderr || fail "--resume in one process failed"
  cat one_after.stderr
  grep -q "gathering [1-9]" one_after.stderr || fail "one process did not gather from the ranks' checkpoints"
  "$python" "$compare" reference.h5 two_then_one.h5 || fail "$ranks ranks then one process differs"
  left=$(ls two_then_one.h5.checkpoint* 2>/dev/null)
  [ -z "$left" ] || fail "checkpoints left behind: $left"
  ;;
finished_rank)
  # R = 3 on 2 ranks: rank 0 runs realizations 0 and 1 one after the other,
  # rank 1 realization 2, so rank 1 ends about halfway through rank 0's work
  # (a few seconds each here). Rank 1 must keep its checkpoint after its block
  # is sent, or the resume would run realization 2 again.
  run=(-N 20000 -r 0.9 -d 1e-2 --subthreshold elastic --engine hybrid -t 10000 --histogram-times 100,10000
       -R 3 -s 5 -j 1 -q)
  "$sim" "${run[@]}" -o reference.h5 || fail "the uninterrupted run failed"
  # Rank 1's last checkpoint, written when its block ends, has none in progress.
  interrupt_once_rank1_finished "rank 1\]: checkpoint: 0 realizations in progress" "${run[@]}"
  resume_equals_reference "rank 1\]: resuming from .*: 1 realizations done, 0 continue" "${run[@]}"
  ;;
complete_output)
  "${mpiexec[@]}" "$ranks" "$sim" "${physics[@]}" -R 3 -j 1 -o done.h5 || fail "mpirun -np $ranks run failed"
  cp done.h5 kept.h5
  start=$SECONDS
  "${mpiexec[@]}" "$ranks" "$sim" "${physics[@]}" -R 3 -j 1 --resume -o done.h5 2>again.stderr ||
    fail "mpirun -np $ranks --resume over the complete output failed: $(cat again.stderr)"
  cat again.stderr
  [ "$(grep -c . again.stderr)" -eq 1 ] &&
    grep -q "^shockgas-sim: 'done.h5' is already a complete output of this run; nothing to do" again.stderr ||
    fail "expected one line saying there is nothing to do"
  cmp -s kept.h5 done.h5 || fail "--resume over the complete output rewrote it"
  [ $((SECONDS - start)) -lt 60 ] || fail "the ranks did not leave together"
  ;;
*)
  fail "unknown case '$case_name'"
  ;;
esac
echo "ok: $case_name"
