#!/usr/bin/env bash
# install_test.sh BUILD_DIR SOURCE_DIR PYTHON (label install; docs/install.md)
# Installs the build into a fresh prefix in a temporary folder outside the
# source tree, then, from there, uses it as a user would:
#   1. shockgas-sim --help and --version from the prefix's bin/, and a small run;
#   2. a consumer project (tests/install/consumer, ~20 lines) finds the package
#      with find_package(shockgas), links shockgas::sim, runs the event engine
#      and prints T; that T must equal, to the last bit, the T the installed
#      shockgas-sim wrote for the same parameters and seed; and docs/library.md's
#      program, as the page writes it, writes the file shockgas-sim writes;
#   3. the Python module is imported from the prefix (not the source tree) and
#      reads that run;
#   4. the installed figure project (share/shockgas) builds Fig. 3 with the
#      installed programs;
#   5. the man pages are there and hold the programs' options.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3
fail() { echo "FAIL: $*"; exit 1; }

outside=$(mktemp -d "${TMPDIR:-/tmp}/shockgas-install-test.XXXXXX")
trap 'rm -rf "$outside"' EXIT
case "$outside/" in "$source"/*) fail "the temporary folder $outside is inside the source tree" ;; esac
prefix="$outside/prefix"
cmake --install "$build" --prefix "$prefix" >"$outside/install.log" || { cat "$outside/install.log"; fail "cmake --install"; }
cd "$outside"

# 1. The programs, from the prefix.
export PATH="$prefix/bin:$PATH"
[ "$(command -v shockgas-sim)" = "$prefix/bin/shockgas-sim" ] || fail "shockgas-sim is not the installed one"
# Not grep -q: it stops reading at the match, and under pipefail the writer's SIGPIPE fails the line.
shockgas-sim --help | grep -- "--restitution" >/dev/null || fail "shockgas-sim --help lacks --restitution"
shockgas-sim --version | grep -q "^shockgas-sim " || fail "shockgas-sim --version: $(shockgas-sim --version)"
for program in shockgas-merge shockgas-dump shockgas-burgers shockgas-analyze shockgas-tail shockgas-plan shockgas-look; do
  "$program" --help >/dev/null || fail "$program --help"
  "$program" --version | grep "^$program [^ ]" >/dev/null || fail "$program --version: $("$program" --version 2>&1)"
done
# The consumer's run: N = 1000, r = 0.9, delta = 1e-2, seed 1, realization 0, to t = 10.
shockgas-sim -N 1000 -r 0.9 -d 1e-2 -s 1 -R 1 -t 10 -j 1 -q -o run.h5 || fail "the small run"
[ -s run.h5 ] || fail "no run.h5"
# shockgas-look from the prefix finds its gnuplot script in share/shockgas/figures.
if command -v gnuplot >/dev/null; then
  shockgas-sim -N 2000 -r 0.5 -t 3000 -R 2 -q -o look.h5 2>/dev/null || fail "the run for shockgas-look"
  shockgas-look look.h5 -o look.png >look.log 2>&1 || { cat look.log; fail "shockgas-look"; }
  [ -s look.png ] || fail "shockgas-look wrote no look.png"
  # ...and with the prefix off PATH, from a PATH holding only the commands it needs besides ours:
  # it runs the shockgas-analyze and shockgas-dump installed beside it.
  mkdir bare-path
  for command in bash readlink dirname mktemp rm sed tr basename cat gnuplot; do
    ln -s "$(command -v "$command")" bare-path/
  done
  PATH="$outside/bare-path" "$prefix/bin/shockgas-look" --version | grep "^shockgas-look [^ ]" >/dev/null \
    || fail "shockgas-look off PATH: --version: $(PATH="$outside/bare-path" "$prefix/bin/shockgas-look" --version 2>&1)"
  PATH="$outside/bare-path" "$prefix/bin/shockgas-look" look.h5 -o look-off-path.png >look-off-path.log 2>&1 \
    || { cat look-off-path.log; fail "shockgas-look with the prefix off PATH"; }
  [ -s look-off-path.png ] || fail "shockgas-look off PATH wrote no look-off-path.png"
fi

# 2. A project of the user's own, built against the installed package.
cmake -S "$source/tests/install/consumer" -B consumer -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >consumer.log 2>&1 || { cat consumer.log; fail "configuring the consumer project (find_package(shockgas))"; }
cmake --build consumer >>consumer.log 2>&1 || { cat consumer.log; fail "building the consumer project"; }
consumer_line=$(./consumer/consumer)
echo "consumer: $consumer_line"
consumer_T=${consumer_line##* T }

# 2b. docs/library.md's program, as the page writes it: built against the package, run, its file equal
# bit for bit to shockgas-sim's for the same parameters, and its input check refusing r = 1.5 in one line.
mkdir library && "$python" - "$source/docs/library.md" library <<'PYTHON' || fail "docs/library.md: no program and CMakeLists.txt"
import re, sys
page, out = open(sys.argv[1], encoding="utf-8").read(), sys.argv[2]
blocks = re.findall(r"```(cpp|cmake)\n(.*?)```", page, re.S)
program = next(code for kind, code in blocks if kind == "cpp" and code.startswith("// my_ensemble.cpp"))
cmake = next(code for kind, code in blocks if kind == "cmake" and code.startswith("# CMakeLists.txt"))
open(f"{out}/my_ensemble.cpp", "w").write(program)
open(f"{out}/CMakeLists.txt", "w").write(cmake)
PYTHON
(cd library && cmake -S . -B build -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >build.log 2>&1 &&
  cmake --build build >>build.log 2>&1) || { cat library/build.log; fail "building docs/library.md's program"; }
(cd library && ./build/my_ensemble) >library/run.log || fail "docs/library.md's program: $(cat library/run.log)"
grep -Eq '^[a-z]+ engine, [0-9]+ collisions: T\(1000\) = 0\.[0-9]+' library/run.log || fail "its line: $(cat library/run.log)"
shockgas-sim -N 10000 -r 0.9 -d 1e-2 --subthreshold elastic -t 1000 -R 4 -s 7 --engine auto -q -o library/sim.h5 \
  2>/dev/null || fail "shockgas-sim with docs/library.md's parameters"
"$python" "$source/tests/compare_outputs.py" library/sim.h5 library/my_ensemble.h5 >library/compare.log ||
  fail "docs/library.md's file differs from shockgas-sim's: $(cat library/compare.log)"
status=0
refusal=$(cd library && ./build/my_ensemble 1.5 2>&1) || status=$?
[ "$status" = 2 ] && [ "$refusal" = "my_ensemble: error: restitution r must lie in [0, 1], got 1.5" ] ||
  fail "docs/library.md's program with r = 1.5: status $status, '$refusal'"
echo "docs/library.md: $(cat library/run.log); its file equals shockgas-sim's"

# 3. The Python module, from the prefix's module folder only.
module_dir=$(ls -d "$prefix"/lib/python3*/site-packages)
python_T=$(cd "$outside" && PYTHONPATH="$module_dir" "$python" -s -c '
import sys, numpy as np, shockgas
assert shockgas.__file__.startswith(sys.argv[1]), shockgas.__file__
run = shockgas.read_run("run.h5")
assert run.attrs["status"] == "complete" and isinstance(run.attrs["version"], str)
k = int(np.flatnonzero(run.time == 10.0)[0])
print(repr(float(run.temperature[0, k])))' "$prefix") || fail "reading run.h5 with the installed module"
echo "shockgas-sim, read by the installed module: T(10) = $python_T"
"$python" -c 'import sys; a, b = map(float, sys.argv[1:]); sys.exit(0 if a == b and 0 < a < 1 / 3 else 1)' \
  "$consumer_T" "$python_T" || fail "the library's T ($consumer_T) is not the program's ($python_T), or not in (0, 1/3)"
# The installed reproduce-check (share/shockgas/tools, with shockgas_path.py beside it) runs on the
# installed module's shockgas.archive and shockgas.compare: an archive that is not there is its one line.
status=0
line=$(cd "$outside" && PYTHONPATH="$module_dir" "$python" -s "$prefix/share/shockgas/tools/reproduce-check" \
  no-such-archive.tar.gz 2>&1) || status=$?
[ "$status" = 2 ] && [ "$line" = "reproduce-check: error: no-such-archive.tar.gz: no such file" ] ||
  fail "the installed reproduce-check (exit $status): $line"

# 4. The figures from the installed copy: Fig. 3 (a run of < 1 s and gnuplot).
cmake -S "$prefix/share/shockgas" -B figures -DSHOCKGAS_PYTHON="$python" >figures.log 2>&1 \
  || { cat figures.log; fail "configuring the installed figure project"; }
cmake --build figures --target fig3 >>figures.log 2>&1 || { cat figures.log; fail "building fig3 from the installed copy"; }
head -c 8 figures/figures/quick/fig3.png | grep -q PNG || fail "no fig3.png from the installed copy"
grep -q "^%PDF" figures/figures/quick/fig3.pdf || fail "no fig3.pdf from the installed copy"

# 5. Man pages.
for program in shockgas-sim shockgas-merge shockgas-dump shockgas-burgers shockgas-analyze shockgas-plan; do
  page="$prefix/share/man/man1/$program.1.gz"
  gzip -dc "$page" | grep "^\.TH \"\?${program^^}" >/dev/null || fail "$page is not a man page of $program"
done
gzip -dc "$prefix/share/man/man1/shockgas-sim.1.gz" | grep -- "restitution" >/dev/null || fail "shockgas-sim.1 lacks its options"
gzip -dc "$prefix/share/man/man1/shockgas-analyze.1.gz" | grep -- "decay" >/dev/null || fail "shockgas-analyze.1 lacks its subcommands"
gzip -dc "$prefix/share/man/man1/shockgas-plan.1.gz" | grep -- "tolerance" >/dev/null || fail "shockgas-plan.1 lacks its options"
echo "ok: installed into $prefix and used from outside the source tree"
