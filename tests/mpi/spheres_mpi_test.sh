#!/usr/bin/env bash
# spheres_mpi_test.sh CASE SPHERES PYTHON WORK_DIR MPIEXEC...: end-to-end tests
# of `mpirun -np 2 shockgas-spheres` (tests/mpi/CMakeLists.txt registers them).
#   spheres_identical      3 realizations over 2 ranks (2 + 1) give the datasets
#                          of a one-process run bit for bit; another seed does not
#   spheres_idle_rank      1 realization over 2 ranks: rank 1 idles, same file
#   spheres_failing_rank   a rank with an invalid argument, or one that cannot
#                          send its block, fails the job with a line naming it,
#                          no output file and no hang
#   spheres_finished_rank  Ctrl-C once rank 1 has finished its block, before rank 0
#                          has: every rank keeps its checkpoint, a resume in one
#                          process is refused with the rank count to use, the
#                          resume on 2 ranks takes rank 1's realization from its
#                          checkpoint, the file equals an uninterrupted run's bit
#                          for bit, and no checkpoint is left behind
# MPIEXEC... is the launcher and its process-count flag, e.g. "mpiexec -n".
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
case_name=$1 spheres=$2 python=$3 work=$4
shift 4
mpiexec=("$@")
here=$(cd "$(dirname "$0")" && pwd)
compare="$here/../compare_outputs.py"
ranks=2

# Disks at r = 0.9, delta = 1e-2, with snapshots and histograms so that every
# dataset kind is compared; about 0.1 CPU-s a realization.
physics=(-D 2 -N 2000 --phi 0.2 -r 0.9 -d 1e-2 -t 30 --snapshot-times 3,30 --histogram-times 3,30 --field-cells 8)

program=$spheres
# shellcheck source=mpi_common.sh
. "$here/mpi_common.sh"
enter_work_folder "$work"

case "$case_name" in
spheres_identical)
  check_identical 3  # 2 + 1: uneven on purpose
  ;;
spheres_idle_rank)
  check_idle_rank
  ;;
spheres_failing_rank)
  check_failing_rank "restitution" --restitution 1.5
  ls reduce.h5.checkpoint.rank* >/dev/null 2>&1 || fail "a failed job removed the ranks' checkpoints"
  ;;
spheres_finished_rank)
  # R = 3 on 2 ranks: rank 0 runs realizations 0 and 1 one after the other,
  # rank 1 realization 2, so rank 1 ends about halfway through rank 0's work
  # (about 4 s each here).
  run=(-D 2 -N 50000 --phi 0.2 -r 0.9 -d 1e-2 -t 400 --field-cells 8 --snapshot-times 40 --histogram-times 40
       -R 3 -s 5 -j 1)
  "$spheres" "${run[@]}" -o reference.h5 || fail "the uninterrupted run failed"
  interrupt_once_rank1_finished "rank 1\]: checkpoint: every realization finished" "${run[@]}"
  for k in 0 1; do
    [ -e stopped.h5.checkpoint.rank$k ] || fail "no checkpoint of rank $k: $(cat stopped.stderr)"
  done
  [ ! -e stopped.h5 ] || fail "an interrupted job wrote an output"
  if "$spheres" "${run[@]}" --resume -o stopped.h5 2>one.stderr; then fail "one process resumed a 2-rank job's checkpoints"; fi
  cat one.stderr
  grep -q "from a job of 2 ranks: resume it with mpirun -np 2" one.stderr || fail "the refusal does not name the rank count"
  resume_equals_reference "rank 1\]: resuming from .*: 1 realizations finished, 0 under way" "${run[@]}"
  ;;
*)
  fail "unknown case '$case_name'"
  ;;
esac
