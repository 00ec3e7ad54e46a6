#!/usr/bin/env bash
# progress_report_test.sh SIM PYTHON REPORT WORK_DIR: tools/fidelity_report.py --progress on a paper
# build in progress, made up of Fig. 4's run names: a finished part of r0.5 (2 realizations), a
# running part of r0.5 caught in its checkpoint, nothing yet of r0.9. The report must count the
# finished part, read the checkpoint's CPU time and progress, and extrapolate the rest of r0.5
# from its finished part (the 19 other parts of Fig. 4's 20 at that part's CPU time).
set -u
sim=$1 python=$2 report=$3 work=$4
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
"$python" "$report" "$work" paper --progress >report.md || fail "the report failed: $(cat report.md)"
cat report.md
line=$(grep '^| fig4 | r0.5 |' report.md) || fail "no line for fig4's r0.5"
cpu_part=$("$python" -c 'import sys; sys.path.insert(0, sys.argv[2]); import shockgas
print(f"{shockgas.attributes(sys.argv[1])[sys.argv[3]] * 19:.0f}")' r0.5.part0.h5 "$here/../../python" cpu_seconds)
case "$line" in
  "| fig4 | r0.5 | 1/20 | 2/200 | "*"| part10: 0/3 done, one at t = "*" | $cpu_part |") ;;
  *) fail "r0.5's line is not as expected (remaining CPU $cpu_part s): $line" ;;
esac
grep -q '^| fig4 | r0.9 | 0/20 | 0/200 | 0 | — | — |$' report.md || fail "r0.9 should show nothing done"
echo "ok"
