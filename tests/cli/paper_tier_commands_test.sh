#!/usr/bin/env bash
# paper_tier_commands_test.sh TOOL PYTHON SOURCE_DIR CI_BUILD WORK_DIR: `tools/paper-tier commands`, which
# prints the figure pipeline's simulations as shell commands for running them outside the build (a
# cluster's job array), the outputs then taken as made by the build.
#  1. A paper-fidelity tree of SOURCE_DIR, configured only (nothing is built or run): without the
#     simulator's stamp the tool refuses with the command that builds it; with it, fig4's 41 runs (r = 0
#     and the 20 parts each of r = 0.5 and 0.9) come out, each the very shockgas-sim command of its rule
#     in the build's Makefile, and the runs already there are left out; a target without runs is an error.
#  2. Make takes outputs put in place by such commands as made: with r = 0.5's 20 parts present, the rule
#     of r0.5.h5 merges them and runs no simulation; with them absent it runs them (the control).
#  3. One command run for real: fig3's (CI_BUILD's quick tree, built by the figures fixture), its output
#     moved to WORK_DIR, equals the pipeline's own file bit for bit (shockgas.compare.identical_runs; the
#     version attribute aside, see below).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
tool=$1 python=$2 source=$3 ci_build=$4 work=$5
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || exit 1
build=$work/paper
cmake -S "$source" -B "$build" -DSHOCKGAS_FIDELITY=paper -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" 2>&1 ||
  fail "the paper tree did not configure: $(tail -n 5 "$work/configure.log")"

# 1. The stamp first; then the commands, one per run not yet there.
out=$("$tool" commands --build "$build" fig4 2>&1)
[ $? -eq 2 ] || fail "commands without the simulator's stamp did not exit 2: $out"
grep -qF "cmake --build '$build' --target shockgas_sim_stamp" <<<"$out" || fail "no hint to build the stamp: $out"
# A stand-in for the stamp (this tree builds nothing): the outputs below are made after it, as on a cluster.
touch "$build/shockgas-sim.stamp" || exit 1
"$tool" commands --build "$build" fig4 >"$work/fig4.commands" 2>"$work/fig4.summary" || fail "commands failed"
[ "$(wc -l <"$work/fig4.commands")" -eq 41 ] || fail "$(wc -l <"$work/fig4.commands") commands for fig4, not 41"
grep -qF "41 simulation command(s) of fig4" "$work/fig4.summary" || fail "summary: $(cat "$work/fig4.summary")"
# A target with no list (fig_tail's sampler is no shockgas-sim run; so is every figure of a tree configured
# before the lists existed) is an error, not "0 commands", which would read as "nothing left to run".
out=$("$tool" commands --build "$build" fig_tail 2>&1)
[ $? -eq 2 ] && grep -qF "lists no simulations of fig_tail" <<<"$out" || fail "fig_tail: $out"
"$python" - "$work/fig4.commands" "$build/paper_targets/CMakeFiles/fig4.dir/build.make" <<'EOF' || fail "a command is not its rule's"
import os, shlex, sys
commands, makefile = sys.argv[1], sys.argv[2]
# The rule's shockgas-sim command for each staged output, as words with the program's path made absolute:
# the rule runs it through cmake/RunSimulation.cmake (cmake -DOUTPUT=... -DSTAGED=... -DINPUTS=... -P
# RunSimulation.cmake -- <program> <arguments>), which renames STAGED to OUTPUT as the command's mv does.
rules = {}
for line in open(makefile):
    if not line.startswith("\tcd ") or "shockgas-sim " not in line:
        continue
    words = shlex.split(line.strip())
    assert words[0] == "cd" and words[2] == "&&", line
    p = words.index("-P")
    assert words[p + 1].endswith("/cmake/RunSimulation.cmake") and words[p + 2] == "--", line
    defined = dict(w[2:].split("=", 1) for w in words[4:p] if w.startswith("-D"))
    directory, program = words[1], words[p + 3]
    words = [os.path.normpath(os.path.join(directory, program))] + words[p + 4:]
    staged = words[words.index("--output") + 1]
    assert defined["STAGED"] == staged and defined["OUTPUT"] == staged.replace(".running.h5", ".h5"), defined
    rules[staged] = (directory, words)
seen = 0
for line in open(commands):
    words = shlex.split(line)
    assert words[0] == "cd" and words[2] == "&&", line
    end = words.index("&&", 3)
    directory, command, move = words[1], words[3:end], words[end + 1:]
    staged = command[command.index("--output") + 1]
    assert staged in rules, f"no rule writes {staged}"
    assert (directory, command) == rules[staged], f"{command} differs from the rule's {rules[staged]}"
    assert move[:2] == ["mv", "-f"] and move[2] == staged and move[3] == staged.replace(".running.h5", ".h5"), move
    seen += 1
assert seen == 41 and len(rules) == 41, (seen, len(rules))
print(f"the {seen} commands are their rules' commands")
EOF

# 2. Outputs made outside the build, newer than the stamp and the .args files: make only merges.
runs=$build/paper_targets/paper/fig4
merge_plan() { (cd "$build" && make -n -f paper_targets/CMakeFiles/fig4.dir/build.make "paper_targets/paper/fig4/r0.5.h5"); }
plan=$(merge_plan) || fail "make -n failed: $plan"
grep -q "shockgas-sim " <<<"$plan" || fail "the control: without the parts make would not run them"
sleep 1  # coarse file times: the parts must be strictly newer than the stamp and the .args files
for ((first = 0; first < 200; first += 10)); do touch "$runs/r0.5.part$first.h5" || exit 1; done
plan=$(merge_plan) || fail "make -n failed: $plan"
grep -q "shockgas-sim " <<<"$plan" && fail "make would run a simulation whose output is there: $plan"
grep -q "shockgas-merge " <<<"$plan" || fail "make would not merge the parts: $plan"
"$tool" commands --build "$build" fig4 >"$work/left.commands" 2>/dev/null || fail "commands failed"
[ "$(wc -l <"$work/left.commands")" -eq 21 ] || fail "$(wc -l <"$work/left.commands") commands left, not 21 (r = 0 and r = 0.9's parts)"
grep -q "r0\.5\.part" "$work/left.commands" && fail "a run that is there was listed"

# 3. Run fig3's command, writing into WORK_DIR instead of the quick tree, and compare with the pipeline's.
fig3=$ci_build/paper_targets/quick/fig3
[ -f "$fig3/worldlines.h5" ] || fail "no '$fig3/worldlines.h5' (the figures fixture makes it)"
command=$("$tool" commands --build "$ci_build" --all fig3 2>/dev/null) || fail "commands --all failed"
[ "$(wc -l <<<"$command")" -eq 1 ] || fail "fig3 has one run: $command"
mkdir -p "$work/fig3" || exit 1
command=${command//"'$fig3/"/"'$work/fig3/"}
grep -qF "$work/fig3/worldlines.running.h5" <<<"$command" || fail "the output was not moved: $command"
bash -c "$command" || fail "the command failed: $command"
# Bit for bit but for `version`: the pipeline reruns a run only when the simulator's sources change (its
# stamp), so a tree rebuilt at a later commit keeps files that name the commit they were made at. The
# simulator_sha256 attribute, which hashes those sources, is compared with everything else.
"$python" - "$fig3/worldlines.h5" "$work/fig3/worldlines.h5" <<'EOF' ||
import sys
from shockgas.compare import identical_runs
problems, datasets = identical_runs(sys.argv[1], sys.argv[2])
problems = [p for p in problems if not p.startswith("attribute version of / differs")]
for problem in problems:
    print(f"FAIL: {problem}")
print(f"{datasets} datasets compared")
sys.exit(1 if problems else 0)
EOF
  fail "the command's output differs from the pipeline's"
echo "PASS"
