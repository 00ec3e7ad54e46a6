# SPDX-License-Identifier: GPL-3.0-or-later
# What the MPI end-to-end tests share (sourced by mpi_test.sh and
# spheres_mpi_test.sh, after they set program, physics, python, compare,
# mpiexec and ranks): the launcher's environment, the work folder, and the
# cases both programs pass the same way.

# Open MPI refuses root without these, and by default binds each rank to
# one core and refuses more ranks than cores; a test machine may be a
# container run as root with few cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_hwloc_base_binding_policy=none
# Containers often forbid the cross-memory attach Open MPI uses for large
# messages on one node; plain copies work everywhere.
export OMPI_MCA_btl_vader_single_copy_mechanism=none

fail() { echo "FAIL: $*"; exit 1; }

enter_work_folder() {
  mkdir -p "$1" && cd "$1" || fail "cannot enter $1"
  rm -f ./*.h5 ./*.h5.* ./*.stderr
}

# R realizations on $ranks ranks give the one-process run's file bit for bit,
# and the comparison catches another seed (it must be able to fail).
check_identical() {
  local realizations=$1
  "$program" "${physics[@]}" -R "$realizations" -s 7 -o single.h5 || fail "single-process run failed"
  "${mpiexec[@]}" "$ranks" "$program" "${physics[@]}" -R "$realizations" -s 7 -j 1 -o distributed.h5 ||
    fail "mpirun -np $ranks run failed"
  "$python" "$compare" single.h5 distributed.h5 "$ranks" || fail "the distributed file differs from the single run"
  "$program" "${physics[@]}" -R "$realizations" -s 8 -o other_seed.h5 || fail "single-process run (seed 8) failed"
  if "$python" "$compare" other_seed.h5 distributed.h5 "$ranks" >other_seed.stderr; then
    fail "compare_outputs.py accepted files from different seeds"
  fi
  grep -q "dataset /timeseries/temperature differs" other_seed.stderr ||
    fail "compare_outputs.py rejected seed 8 without naming the temperature: $(cat other_seed.stderr)"
  echo "ok: a different seed is caught"
}

# One realization on $ranks ranks: the others idle, the file is the same.
check_idle_rank() {
  "$program" "${physics[@]}" -R 1 -o single.h5 || fail "single-process run failed"
  "${mpiexec[@]}" "$ranks" "$program" "${physics[@]}" -R 1 -j 1 -o distributed.h5 ||
    fail "mpirun -np $ranks run with one realization failed"
  "$python" "$compare" single.h5 distributed.h5 "$ranks" || fail "the distributed file differs from the single run"
}

# Rank 1 cannot start (BAD_OPTION... on its command line, whose message
# contains $1), then cannot send its block (no temporary folder): the job
# fails with a line naming rank 1, writes no output, and does not hang.
check_failing_rank() {
  local message=$1
  shift
  if "${mpiexec[@]}" 1 "$program" "${physics[@]}" -R 4 -o setup.h5 : \
     "${mpiexec[@]:1}" 1 "$program" "${physics[@]}" -R 4 "$@" -o setup.h5 2>setup.stderr; then
    fail "the job succeeded although rank 1 had an invalid argument"
  fi
  cat setup.stderr
  grep -q "rank 1 of 2 failed before the run" setup.stderr || fail "no line naming rank 1 (setup)"
  grep -q "$message" setup.stderr || fail "rank 1's own error is missing"
  [ ! -e setup.h5 ] || fail "setup.h5 written by a failed job"
  if "${mpiexec[@]}" 1 "$program" "${physics[@]}" -R 4 -o reduce.h5 : \
     "${mpiexec[@]:1}" 1 env TMPDIR=/nonexistent/shockgas "$program" "${physics[@]}" -R 4 -o reduce.h5 \
     2>reduce.stderr; then
    fail "the job succeeded although rank 1 could not send its block"
  fi
  cat reduce.stderr
  grep -q "rank 1 of 2 could not send its realizations" reduce.stderr || fail "no line naming rank 1 (reduce)"
  [ ! -e reduce.h5 ] || fail "reduce.h5 written by a failed job"
}

# Starts `mpirun -np $ranks $program RUN... --checkpoint-interval 0.3 -o
# stopped.h5`, waits until rank 1's stderr line matching PATTERN says its block
# is finished (rank 0 still running), and interrupts the job, which must not
# have finished. Its stderr is stopped.stderr.
interrupt_once_rank1_finished() {
  local pattern=$1
  shift
  "${mpiexec[@]}" "$ranks" "$program" "$@" --checkpoint-interval 0.3 -o stopped.h5 2>stopped.stderr &
  local launcher=$!
  for _ in $(seq 1 600); do
    grep -q "$pattern" stopped.stderr && break
    sleep 0.1
  done
  grep -q "$pattern" stopped.stderr ||
    { kill -INT "$launcher"; wait "$launcher"; fail "rank 1 wrote no checkpoint when its block ended: $(cat stopped.stderr)"; }
  kill -INT "$launcher"
  wait "$launcher" && fail "the job finished before the interrupt: the test did not test"
  [ -e stopped.h5.checkpoint.rank1 ] || fail "rank 1 kept no checkpoint of its finished block: $(cat stopped.stderr)"
}

# Resumes that job on $ranks ranks: rank 1's line matching PATTERN says it took
# its finished realization from its checkpoint, the file equals reference.h5
# bit for bit, and no checkpoint is left behind.
resume_equals_reference() {
  local pattern=$1
  shift
  "${mpiexec[@]}" "$ranks" "$program" "$@" --resume -o stopped.h5 2>resumed.stderr ||
    fail "mpirun -np $ranks --resume failed: $(cat resumed.stderr)"
  cat resumed.stderr
  grep -q "$pattern" resumed.stderr || fail "rank 1 did not take its finished realization from its checkpoint"
  "$python" "$compare" reference.h5 stopped.h5 "$ranks" || fail "the resumed file differs from the uninterrupted run"
  local left
  left=$(ls stopped.h5.checkpoint* 2>/dev/null)
  [ -z "$left" ] || fail "checkpoints left behind: $left"
}
