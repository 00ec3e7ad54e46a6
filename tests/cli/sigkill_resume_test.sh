#!/usr/bin/env bash
# sigkill_resume_test.sh SIM PYTHON COMPARE_OUTPUTS DIR
# A run killed with SIGKILL (no chance to clean up) and continued with
# --resume writes exactly the file an uninterrupted run writes:
#   1. an uninterrupted reference run;
#   2. the same run with a checkpoint every 0.3 s, killed with kill -9 once
#      its second checkpoint is on disk: it must leave no output file (the
#      output is written atomically), only the checkpoint;
#   3. `--resume`: must say it resumed, finish, remove the checkpoint, and
#      give datasets bit-identical to the reference (compare_outputs.py).
# The test fails, rather than passing vacuously, if the run ends before it
# can be killed.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
sim=$1 python=$2 same=$3 dir=$4
source "$(dirname "$0")/checkpoint_helpers.sh"
mkdir -p "$dir"
cd "$dir" || exit 1
rm -f reference.h5 killed.h5 killed.h5.checkpoint ./*.err
# About 5-10 s of CPU on 2 threads: long enough to be killed mid-way after
# two checkpoints even on a busy machine.
args=(-N 100000 -r 0.9 -d 0.01 -t 1000 -R 2 -j 2 -q --seed 11 --histogram-times 100,1000 --snapshot-times 30,300)

"$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || { cat reference.err; echo "FAIL: reference run"; exit 1; }

# Killed once its second checkpoint is on disk (the first may be taken before any event).
run_until_checkpoints 2 9 killed.err -- "$sim" "${args[@]}" --checkpoint-interval 0.3 -o killed.h5
cat killed.err
[ -e killed.h5 ] && { echo "FAIL: the run finished (or left an output) before SIGKILL: make it longer"; exit 1; }
[ -s killed.h5.checkpoint ] || { echo "FAIL: no checkpoint after SIGKILL"; exit 1; }

"$sim" "${args[@]}" --checkpoint-interval 0.3 --resume -o killed.h5 2>resumed.err || { cat resumed.err; echo "FAIL: resumed run"; exit 1; }
cat resumed.err
grep -q "resuming from 'killed.h5.checkpoint'.* [12] continue" resumed.err ||
  { echo "FAIL: the resumed run did not continue from the checkpoint"; exit 1; }
[ -e killed.h5.checkpoint ] && { echo "FAIL: checkpoint left behind after a complete run"; exit 1; }
"$python" "$same" reference.h5 killed.h5 || { echo "FAIL: resumed output differs from the uninterrupted run"; exit 1; }
echo "ok: killed with SIGKILL, resumed, bit-identical"
