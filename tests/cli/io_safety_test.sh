#!/usr/bin/env bash
# io_safety_test.sh CASE DIR SIM MERGE DUMP [PYTHON]
# Outputs never destroy inputs or other files, and a failed write is an error
# (each case below names what would otherwise happen). The
# refusals are checked as expect_error.sh checks them (exit 2, one line on
# stderr matching the message), and in addition that the file at stake is
# unchanged, which expect_error.sh cannot do (it removes its output first).
#   checkpoint_not_a_checkpoint  --checkpoint naming a run's output (with and without --resume) is
#                                refused and the file kept, not removed at the end of the run
#   checkpoint_is_init           --checkpoint naming the --init file: refused, the init file kept (PYTHON)
#   output_is_init               -o naming the --init file: refused, the init file kept (PYTHON)
#   checkpoint_removed           a run's own checkpoints are still removed once its output is written
#   merge_output_is_part         shockgas-merge -o naming one of its parts: refused, the part kept
#   merge_checkpoint             shockgas-merge of a checkpoint: refused, saying it is a checkpoint
#   dump_output_is_input         shockgas-dump -o naming its input: refused, the input kept (not truncated)
#   dump_outputs                 shockgas-dump writes a file (no temporary left), /dev/null and /dev/stdout
#                                (written through, still devices; a `>> log` kept whole, /dev/fd/3 under
#                                `3>>` appended to), and reports a full disk on -o and on
#                                standard output (> /dev/full) as an error instead of exit 0
#   output_not_an_output         -o naming an existing text file or another program's HDF5 file: refused,
#                                the file kept (not silently replaced); an empty file, and an earlier
#                                output of a run, are still replaced
#   output_not_creatable         -o in a directory where no file can be created (/sys, where even root
#                                cannot): refused before any work; for root, access(W_OK) says yes, and a
#                                run without checkpoints would find out only at its end, its results lost
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
case_name=$1 dir=$2 sim=$3 merge=$4 dump=$5 python=${6:-}
source "$(dirname "$0")/checkpoint_helpers.sh"
mkdir -p "$dir/$case_name"
cd "$dir/$case_name" || exit 1
rm -rf ./*
fail() { echo "FAIL [$case_name]: $*"; for f in ./*.err; do [ -e "$f" ] && { echo "--- $f"; cat "$f"; }; done; exit 1; }
# refused REGEX COMMAND...: exit status 2 and one line on stderr matching REGEX.
refused() {
  local regex=$1
  shift
  "$@" >/dev/null 2>refused.err
  local status=$?
  [ "$status" -eq 2 ] || fail "exit status $status, expected 2: $*"
  [ "$(wc -l <refused.err)" -eq 1 ] || fail "expected one line on stderr: $*"
  grep -Eq -- "$regex" refused.err || fail "stderr does not match /$regex/: $*"
}
kept() { cmp -s "$1" "$2" || fail "'$1' was changed or removed"; }
# An init file (position, velocity, ring_length) written with h5py.
make_init() {
  [ -n "$python" ] || { echo "ok [$case_name]: skipped (no Python with h5py)"; exit 0; }
  "$python" -c 'import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "w") as f:
    f.attrs["ring_length"] = 8.0
    f["position"] = np.arange(8.0)
    f["velocity"] = np.linspace(-1, 1, 8)' "$1" || fail "cannot write an init file"
}
run=(-N 100 -t 10 -q)

case $case_name in
output_not_an_output)
  echo "my notes" >notes.txt
  cp notes.txt notes.kept
  refused "^shockgas-sim: error: 'notes.txt' exists and is not a shockgas-sim output \(not an HDF5 file\): it would be replaced" \
    "$sim" "${run[@]}" -o notes.txt
  kept notes.txt notes.kept
  if [ -n "$python" ]; then
    "$python" -c 'import sys, h5py; h5py.File(sys.argv[1], "w")["data"] = [1.0]' other.h5 || fail "cannot write an HDF5 file"
    cp other.h5 other.kept
    refused "^shockgas-sim: error: 'other.h5' exists and is not a shockgas-sim output \(an HDF5 file without /timeseries\)" \
      "$sim" "${run[@]}" -o other.h5
    kept other.h5 other.kept
  fi
  : >empty.h5
  "$sim" "${run[@]}" -o empty.h5 2>empty.err || fail "an empty file was not replaced by the output"
  "$sim" "${run[@]}" -o empty.h5 2>again.err || fail "a run's earlier output was not replaced"
  ;;
output_not_creatable)
  [ -d /sys ] || { echo "ok [$case_name]: skipped (no /sys)"; exit 0; }
  refused "^shockgas-sim: error: cannot write output '/sys/shockgas-test\.h5': " \
    "$sim" -N 20000 -r 0.8 -d 0.005 -t 1000 -R 2 -q --checkpoint-interval 0 -o /sys/shockgas-test.h5
  ;;
checkpoint_not_a_checkpoint)
  "$sim" "${run[@]}" -o a.h5 2>a.err || fail "the first run"
  cp a.h5 keep.h5
  refused "error: 'keep.h5' exists and is not a shockgas checkpoint \(an HDF5 file without /checkpoint\)" \
    "$sim" "${run[@]}" --checkpoint keep.h5 -o out.h5
  kept keep.h5 a.h5
  refused "error: 'keep.h5' exists and is not a shockgas checkpoint" \
    "$sim" "${run[@]}" --checkpoint keep.h5 --resume -o out.h5
  kept keep.h5 a.h5
  [ ! -e out.h5 ] || fail "an output was written"
  # Neither generation: a text file as the older one.
  echo notes >notes.previous
  cp notes.previous saved
  refused "'notes.previous' exists and is not a shockgas checkpoint \(not an HDF5 file\)" \
    "$sim" "${run[@]}" --checkpoint notes -o out.h5
  kept notes.previous saved
  # The output itself as the checkpoint, before either exists.
  refused "error: checkpoint 'same.h5' is the output 'same.h5': give --checkpoint another path" \
    "$sim" "${run[@]}" --checkpoint same.h5 -o same.h5
  refused "checkpoint 'x' keeps its older generation in 'x.previous', which is the output 'x.previous'" \
    "$sim" "${run[@]}" --checkpoint x -o x.previous
  ;;
checkpoint_is_init)
  make_init init.h5
  cp init.h5 saved
  refused "error: checkpoint 'init.h5' is the init file 'init.h5': give --checkpoint another path" \
    "$sim" --init init.h5 -t 10 -q --checkpoint init.h5 -o out.h5
  kept init.h5 saved
  # The default checkpoint (OUTPUT.checkpoint) as the init file.
  cp init.h5 run.h5.checkpoint
  refused "checkpoint 'run.h5.checkpoint' is the init file 'run.h5.checkpoint'" \
    "$sim" --init run.h5.checkpoint -t 10 -q -o run.h5
  kept run.h5.checkpoint saved
  ;;
output_is_init)
  make_init init.h5
  cp init.h5 saved
  refused "error: output 'init.h5' is the input 'init.h5': it would be overwritten" \
    "$sim" --init init.h5 -t 10 -q -o init.h5
  kept init.h5 saved
  refused "error: output '\./init.h5' is the input 'init.h5'" "$sim" --init init.h5 -t 10 -q -o ./init.h5
  kept init.h5 saved
  ;;
checkpoint_removed)
  # Stopped after its first checkpoint, then resumed to the end: the
  # checkpoints it wrote are removed (only checkpoints are).
  run_until_checkpoints 1 INT stopped.err -- "$sim" -N 20000 -r 0.8 -d 0.005 -t 400 -q --checkpoint-interval 0.1 -o run.h5
  [ -e run.h5.checkpoint ] || fail "no checkpoint to resume from"
  "$sim" -N 20000 -r 0.8 -d 0.005 -t 400 -q --checkpoint-interval 0 --resume -o run.h5 2>resumed.err ||
    fail "the resumed run failed"
  grep -q "resuming from 'run.h5.checkpoint'" resumed.err || fail "did not resume from the checkpoint"
  [ ! -e run.h5.checkpoint ] && [ ! -e run.h5.checkpoint.previous ] || fail "the run's checkpoints were left"
  ;;
merge_output_is_part)
  "$sim" "${run[@]}" -o q0.h5 2>q0.err || fail "part 0"
  "$sim" "${run[@]}" --first-realization 1 -o q1.h5 2>q1.err || fail "part 1"
  cp q0.h5 saved
  refused "^shockgas-merge: error: output 'q0.h5' is the input 'q0.h5': it would be overwritten$" \
    "$merge" q0.h5 q1.h5 -o q0.h5
  kept q0.h5 saved
  "$merge" q0.h5 q1.h5 -o merged.h5 2>merged.err || fail "an ordinary merge failed"
  ;;
merge_checkpoint)
  run_until_checkpoints 1 INT stopped.err -- "$sim" -N 20000 -r 0.5 -d 0.001 -t 1e6 -R 2 -j 1 -q \
    --checkpoint-interval 0.1 -o ck.h5
  [ -e ck.h5.checkpoint ] || fail "no checkpoint was written"
  refused "^shockgas-merge: error: 'ck.h5.checkpoint' is a shockgas-sim checkpoint \(a run in progress\), not an output: continue the run with shockgas-sim --resume" \
    "$merge" ck.h5.checkpoint -o mck.h5
  [ ! -e mck.h5 ] || fail "a merged file was written"
  ;;
dump_output_is_input)
  "$sim" "${run[@]}" --snapshot-times 1,5 -o s_in.h5 2>s.err || fail "the run"
  cp s_in.h5 saved
  refused "^shockgas-dump: error: output 's_in.h5' is the input 's_in.h5': it would be overwritten$" \
    "$dump" snapshots s_in.h5 -o s_in.h5
  kept s_in.h5 saved
  refused "output 's_in.h5' is the input" "$dump" gnuplot-vars s_in.h5 / -o s_in.h5
  kept s_in.h5 saved
  ;;
dump_outputs)
  "$sim" "${run[@]}" --snapshot-times 1,5 -o s.h5 2>s.err || fail "the run"
  "$dump" snapshots s.h5 -o out.txt 2>out.err || fail "a dump to a file failed"
  [ "$(grep -c . out.txt)" -gt 10 ] || fail "the dump is (nearly) empty"
  ls out.txt.tmp.* >/dev/null 2>&1 && fail "a temporary file was left"
  "$dump" snapshots s.h5 -o /dev/null 2>null.err || fail "a dump to /dev/null failed"
  [ -c /dev/null ] || fail "/dev/null is no longer a device"
  "$dump" snapshots s.h5 -o /dev/stdout >stdout.txt 2>stdout.err || fail "a dump to /dev/stdout failed"
  cmp -s stdout.txt out.txt || fail "-o /dev/stdout wrote other text than -o FILE"
  # Under `>> log` the log keeps what it held: /dev/stdout is the log itself, and
  # opening it anew with "w" had truncated it to nothing.
  echo "what the log held before" >log.txt
  "$dump" snapshots s.h5 -o /dev/stdout >>log.txt 2>log.err || fail "a dump to /dev/stdout >> log failed"
  [ "$(head -n 1 log.txt)" = "what the log held before" ] || fail "-o /dev/stdout under >> truncated the log"
  tail -n +2 log.txt | cmp -s - out.txt || fail "-o /dev/stdout under >> wrote other text than -o FILE"
  # A descriptor the shell opened to append (/dev/fd/3 under `3>> log`) is appended to as well.
  echo "what the log held before" >fd3.txt
  "$dump" snapshots s.h5 -o /dev/fd/3 3>>fd3.txt 2>fd3.err || fail "a dump to /dev/fd/3 failed"
  [ "$(head -n 1 fd3.txt)" = "what the log held before" ] || fail "-o /dev/fd/3 under 3>> truncated the file"
  tail -n +2 fd3.txt | cmp -s - out.txt || fail "-o /dev/fd/3 wrote other text than -o FILE"
  refused "^shockgas-dump: error: cannot write '/dev/full': No space left on device$" \
    "$dump" snapshots s.h5 -o /dev/full
  [ -c /dev/full ] || fail "/dev/full is no longer a device"
  "$dump" snapshots s.h5 >/dev/full 2>full.err
  status=$?
  [ "$status" -eq 2 ] || fail "exit status $status writing standard output to /dev/full"
  grep -qx "shockgas-dump: error: cannot write standard output: No space left on device" full.err ||
    fail "no error line for a full standard output"
  "$dump" gnuplot-vars s.h5 / >/dev/full 2>full_vars.err && fail "gnuplot-vars to a full disk exited 0"
  ;;
*) echo "unknown case $case_name"; exit 1 ;;
esac
echo "ok [$case_name]"
