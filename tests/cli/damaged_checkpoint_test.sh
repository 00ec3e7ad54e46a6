#!/usr/bin/env bash
# damaged_checkpoint_test.sh SIM PYTHON COMPARE_OUTPUTS DIR
# A damaged or truncated checkpoint never ends a run and never changes its
# result (docs/reliability.md):
#   1. an uninterrupted reference run;
#   2. the same run with a checkpoint every 0.1 s, stopped (SIGINT) after its
#      third checkpoint: both generations, OUT.h5.checkpoint and
#      OUT.h5.checkpoint.previous, are on disk;
#   3. for bytes overwritten at many offsets of the newest checkpoint, the
#      checkpoint truncated to half, and both generations damaged:
#      `--resume` must exit 0, write datasets bit-identical to the reference
#      (compare_outputs.py), and print at most one warning line, which says
#      what it used instead (the previous checkpoint, or t = 0).
# It also counts the damaged copies that were detected: with checksums on
# every dataset and on the metadata nearly all must be (damage in unused
# bytes of the file changes nothing and may pass).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
sim=$1 python=$2 same=$3 dir=$4
source "$(dirname "$0")/checkpoint_helpers.sh"
mkdir -p "$dir"
cd "$dir" || exit 1
rm -f ./*.h5 ./*.h5.* ./*.err
args=(-N 20000 -r 0.8 -d 0.005 -t 400 -R 2 -j 2 -q --seed 99 --histogram-times 100 --snapshot-times 50)

"$sim" "${args[@]}" --checkpoint-interval 0 -o reference.h5 2>reference.err || { cat reference.err; echo "FAIL: reference run"; exit 1; }

run_until_checkpoints 3 INT stopped.err -- "$sim" "${args[@]}" --checkpoint-interval 0.1 -o run.h5
status=$?
cat stopped.err
[ "$status" -eq 130 ] || { echo "FAIL: the run was not stopped mid-way (exit $status): make it longer"; exit 1; }
[ -s run.h5.checkpoint ] && [ -s run.h5.checkpoint.previous ] ||
  { echo "FAIL: two checkpoint generations expected"; ls -l; exit 1; }
cp run.h5.checkpoint pristine.current
cp run.h5.checkpoint.previous pristine.previous
size=$(stat -c %s pristine.current)

failures=0 detected=0 cases=0
# resume_case NAME: resume from the damaged files in place, check the result.
resume_case() {
  local name=$1
  cases=$((cases + 1))
  rm -f run.h5
  if ! "$sim" "${args[@]}" --checkpoint-interval 0 --resume -o run.h5 2>"$name.err"; then
    cat "$name.err"; echo "FAIL [$name]: the resumed run ended with an error"; failures=$((failures + 1)); return
  fi
  local warnings
  warnings=$(grep -c 'warning' "$name.err")
  if [ "$warnings" -gt 1 ]; then cat "$name.err"; echo "FAIL [$name]: more than one warning line"; failures=$((failures + 1)); fi
  if [ "$warnings" -eq 1 ]; then
    detected=$((detected + 1))
    grep -Eq "warning: .*(resuming from the previous checkpoint|starting from t = 0)" "$name.err" ||
      { cat "$name.err"; echo "FAIL [$name]: the warning does not say what the run used instead"; failures=$((failures + 1)); }
  fi
  if ! "$python" "$same" reference.h5 run.h5 >"$name.cmp" 2>&1; then
    cat "$name.err" "$name.cmp"; echo "FAIL [$name]: the result differs from the uninterrupted run"; failures=$((failures + 1))
  fi
  echo "[$name] $(grep -E 'warning|resuming' "$name.err" | head -2 | tr '\n' ' ')"
}

# Seven bytes overwritten (as in the issue) at offsets spread over the file,
# and in its first kilobyte (superblock and root metadata).
for where in 12 200 700 1pct 10pct 20pct 30pct 40pct 50pct 60pct 70pct 80pct 90pct 99pct; do
  case $where in *pct) offset=$((size * ${where%pct} / 100)) ;; *) offset=$where ;; esac
  cp pristine.current run.h5.checkpoint
  cp pristine.previous run.h5.checkpoint.previous
  printf '\xde\xad\xbe\xef\x01\x02\x03' | dd of=run.h5.checkpoint bs=1 seek="$offset" conv=notrunc status=none
  resume_case "bytes_at_${where}"
done
damaged_cases=$cases

# Truncated to half its size: the previous generation takes over.
cp pristine.current run.h5.checkpoint
cp pristine.previous run.h5.checkpoint.previous
truncate -s $((size / 2)) run.h5.checkpoint
resume_case truncated
grep -q "resuming from the previous checkpoint" truncated.err ||
  { echo "FAIL [truncated]: did not fall back to the previous checkpoint"; failures=$((failures + 1)); }

# Emptied, and its HDF5 signature overwritten: a damaged generation beside an intact previous one,
# not another file that merely has the checkpoint's name: the run goes on from the previous one.
for how in empty signature; do
  cp pristine.current run.h5.checkpoint
  cp pristine.previous run.h5.checkpoint.previous
  case $how in
    empty) : >run.h5.checkpoint ;;
    signature) printf 'XXXXXXXX' | dd of=run.h5.checkpoint bs=1 seek=0 conv=notrunc status=none ;;
  esac
  resume_case "$how"
  grep -q "resuming from the previous checkpoint" "$how.err" ||
    { echo "FAIL [$how]: did not fall back to the previous checkpoint"; failures=$((failures + 1)); }
done

# Both generations damaged: the run starts over, with a warning.
cp pristine.current run.h5.checkpoint
cp pristine.previous run.h5.checkpoint.previous
truncate -s $((size / 2)) run.h5.checkpoint
truncate -s $((size / 3)) run.h5.checkpoint.previous
resume_case both_damaged
grep -q "starting from t = 0" both_damaged.err ||
  { echo "FAIL [both_damaged]: did not start over"; failures=$((failures + 1)); }

# An undamaged pair still resumes silently.
cp pristine.current run.h5.checkpoint
cp pristine.previous run.h5.checkpoint.previous
resume_case intact
grep -q "warning" intact.err && { echo "FAIL [intact]: warned about a good checkpoint"; failures=$((failures + 1)); }
grep -q "resuming from 'run.h5.checkpoint': .* 2 continue" intact.err ||
  { echo "FAIL [intact]: did not resume both realizations mid-way (the stopped run's last checkpoint lost them)"; failures=$((failures + 1)); }

echo "damage detected in $((detected - 4)) of $damaged_cases overwritten copies; $cases resumed runs"
# Overwritten bytes land in checksummed data or metadata except for the
# file's few unused bytes: at least 11 of the 14 copies must be detected.
[ $((detected - 4)) -ge 11 ] || { echo "FAIL: too little damage detected"; failures=$((failures + 1)); }
[ ! -e run.h5.checkpoint ] && [ ! -e run.h5.checkpoint.previous ] ||
  { echo "FAIL: checkpoints left behind after a complete run"; failures=$((failures + 1)); }
[ "$failures" -eq 0 ] || { echo "FAIL: $failures problems"; exit 1; }
echo "ok: every damaged checkpoint gave the uninterrupted result"
