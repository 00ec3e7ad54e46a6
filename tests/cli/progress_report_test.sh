#!/usr/bin/env bash
# progress_report_test.sh SIM SPHERES PYTHON REPORT WORK_DIR: tools/fidelity_report.py --progress on a paper
# build in progress, made up of Fig. 4's run names: a finished part of r0.5 (2 realizations), a
# running part of r0.5 caught in its checkpoint, nothing yet of r0.9. The report must count the
# finished part, read the checkpoint's CPU time and progress, and extrapolate the rest of r0.5
# from its finished part (the 18 parts not begun of Fig. 4's 20 at that part's CPU time, and the running
# one at that time less what its checkpoint has spent); list a checkpoint moved aside by a run of another
# code version, and apart from it one moved aside as another run's (--set-aside-other-runs: parameters
# edited), with its size on disk; and report fig_tail (no parameter file): its sampler running, from paper-tier.log, then done.
# A shockgas-spheres checkpoint (fig_2d's e0.1, of another layout) is read too: its realizations begun,
# the time the furthest reached, its CPU seconds.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
sim=$1 spheres=$2 python=$3 report=$4 work=$5
here=$(cd "$(dirname "$0")" && pwd)
source "$here/checkpoint_helpers.sh"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work/paper_targets/paper/fig4" && cd "$work/paper_targets/paper/fig4" || exit 1
run=(-N 20000 -r 0.5 -d 1e-3 --subthreshold elastic -q)
"$sim" "${run[@]}" -t 50 -R 2 -o r0.5.part0.h5 || fail "the finished part did not run"
# A running part: checkpointed every 0.1 s, then interrupted (SIGKILL: the checkpoint stays as it was).
run_until_checkpoints 2 KILL running.stderr -- "$sim" "${run[@]}" -t 100000 -R 3 --first-realization 10 \
  --checkpoint-interval 0.1 -o r0.5.part10.running.h5
[ -e r0.5.part10.running.h5.checkpoint ] || fail "no checkpoint of the running part: $(cat running.stderr)"
# The CPU times, set to round numbers (1000 s for the finished part, 400 s spent by the running one) so that
# the estimate is exact to read: 18 parts not begun at 1000 s, the running one at 1000 - 400 s. The
# estimate was 19 x 1000 s, counting the running part whole on top of the 400 s already under "so far".
"$python" -c 'import sys, h5py
for path, seconds in (("r0.5.part0.h5", 1000.0), ("r0.5.part10.running.h5.checkpoint", 400.0)):
    with h5py.File(path, "r+") as f:
        f.attrs["cpu_seconds"] = seconds' || fail "could not set the CPU times"
# A checkpoint of another code version moved aside (shockgas-sim keep_aside: both generations): listed
# (not left out of the report), not counted.
cp r0.5.part10.running.h5.checkpoint r0.5.part20.running.h5.checkpoint.from-v1.0-3-gabc1234 &&
  cp r0.5.part10.running.h5.checkpoint r0.5.part20.running.h5.checkpoint.from-v1.0-3-gabc1234.previous || exit 1
# A checkpoint of a run whose parameters were edited, moved aside by --set-aside-other-runs (both
# generations): listed apart, as another run's, with its size on disk, not as "another code version ...
# the old program finishes one" with "(version other-run)".
cp r0.5.part10.running.h5.checkpoint r0.9.running.h5.checkpoint.from-other-run &&
  cp r0.5.part10.running.h5.checkpoint r0.9.running.h5.checkpoint.from-other-run.previous || exit 1
aside_mb=$("$python" -c 'import os, sys; print(f"{sum(os.path.getsize(p) for p in sys.argv[1:]) / 1e6:.1f}")' \
  r0.9.running.h5.checkpoint.from-other-run r0.9.running.h5.checkpoint.from-other-run.previous)
# fig_tail's sampler (no parameter file, no checkpoint) as paper-tier's log shows it running: make's comment,
# then its progress lines (it had no row at all).
printf '%s\n' "[ 50%] [fig_tail] far-tail sampler" "shockgas-tail: progress: 10.0% of the steps  elapsed 60 s  ETA 540 s" \
  "[ 51%] [fig4] something else" "shockgas-tail: progress: 20.0% of the steps  elapsed 120 s  ETA 480 s" \
  >"$work/paper-tier.log"
"$python" "$report" "$work" paper --progress >report.md || fail "the report failed: $(cat report.md)"
# fig_2d's e0.1 (shockgas-spheres, 4 realizations on 2 threads) caught in its checkpoint, its CPU time set
# to 300 s, its two realizations begun stopped after 40 samples of the spheres' grid (0, then 10^(-2 + k/10): the 40th is t = 10^1.8).
mkdir -p "$work/paper_targets/paper/fig_2d" && cd "$work/paper_targets/paper/fig_2d" || exit 1
"$spheres" -D 2 -N 20000 -r 0.8 -R 4 -j 2 -t 1e4 --checkpoint-interval 0 -o e0.1.running.h5 2>spheres.stderr &
spheres_pid=$!
for _ in $(seq 1 600); do [ -e e0.1.running.h5.checkpoint ] && break; sleep 0.02; done
kill -KILL "$spheres_pid" 2>/dev/null; wait "$spheres_pid" 2>/dev/null
[ -e e0.1.running.h5.checkpoint ] || fail "no shockgas-spheres checkpoint: $(cat spheres.stderr)"
"$python" -c 'import h5py
with h5py.File("e0.1.running.h5.checkpoint", "r+") as f:
    f.attrs["cpu_seconds"] = 300.0
    for group in f["realizations"].values():
        group.attrs["samples_done"], group.attrs["finished"] = 40, 0' || fail "could not edit the spheres checkpoint"
cd "$work/paper_targets/paper/fig4" || exit 1
"$python" "$report" "$work" paper --progress >report.md || fail "the report failed: $(cat report.md)"
cat report.md
grep -qF '| fig_2d | e0.1 | 0/1 | 0/4 | 300 | e0.1: 0/4 done, one at t = 63.1 | — |' report.md ||
  fail "fig_2d's running e0.1 (shockgas-spheres): $(grep 'fig_2d | e0.1' report.md)"
line=$(grep '^| fig4 | r0.5 |' report.md) || fail "no line for fig4's r0.5"
case "$line" in
  "| fig4 | r0.5 | 1/20 | 2/200 | 1400 | part10: 0/3 done, one at t = "*" | 18600 |") ;;
  *) fail "r0.5's line is not as expected (CPU 1400 s so far, 18600 s remaining): $line" ;;
esac
grep -q '^| fig4 | r0.9 | 0/20 | 0/200 | 0 | — | — |$' report.md || fail "r0.9 should show nothing done"
grep -qF '| fig_tail | tail (shockgas-tail) | 0/1 | — | 0 | sampler: 20.0% of the steps  elapsed 120 s  ETA 480 s (last progress line in paper-tier.log' report.md ||
  fail "fig_tail's running sampler is not reported"
grep -qF -- '- fig4/r0.5.part20.running.h5.checkpoint.from-v1.0-3-gabc1234 (version v1.0-3-gabc1234): 0/3 realizations done, 400 CPU s' report.md ||
  fail "the checkpoint set aside is not listed"
[ "$(grep -c 'from-v1.0-3-gabc1234' report.md)" = 1 ] || fail "the set-aside checkpoint's two generations are not one entry"
grep -qF -- "- fig4/r0.9.running.h5.checkpoint.from-other-run (another run's parameters): 0/3 realizations done, 400 CPU s; $aside_mb MB on disk (fig4/r0.9.running.h5.checkpoint.from-other-run and fig4/r0.9.running.h5.checkpoint.from-other-run.previous)" report.md ||
  fail "the checkpoint of another run is not listed as one"
grep -q "parameters were edited since .*--set-aside-other-runs.*No build continues one as this run: remove them when no longer wanted" report.md ||
  fail "the checkpoint of another run is not explained as one"
grep -q "version other-run" report.md && fail "the checkpoint of another run is listed as another code version's"
[ "$(grep -c 'from-other-run' report.md)" = 1 ] || fail "the other run's checkpoint is not one entry"
grep -q '^| \*\*all\*\* | | | | \*\*1700\*\* | | \*\*18600\*\*' report.md || fail "the totals: $(grep '^| \*\*all' report.md)"
# Once the sampler has written tail.h5, its row is done with that file's CPU seconds.
mkdir -p "$work/paper_targets/paper/fig_tail" &&
  "$python" -c 'import sys, h5py; import shockgas.schema
with h5py.File(sys.argv[1], "w") as f:
    f.attrs.update({"program": "shockgas-tail", "schema_version": max(shockgas.schema.SCHEMA_VERSIONS),
                    "cpu_seconds": 2029.0, "chains": 4})' "$work/paper_targets/paper/fig_tail/tail.h5" ||
  fail "could not write tail.h5"
"$python" "$report" "$work" paper --progress >report2.md || fail "the second report failed: $(cat report2.md)"
grep -q '^| fig_tail | tail (shockgas-tail) | 1/1 | 4 chains | 2029 | — | — |$' report2.md ||
  fail "fig_tail done: $(grep fig_tail report2.md)"
echo "ok"
