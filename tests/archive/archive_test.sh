#!/bin/bash
# Archival round trip (label archive): archive Fig. 3 (< 1 s of simulation),
# check that it reproduces from its own source in a fresh build directory, then
# check altered copies and expect each alteration to be named.
#   archive_test.sh <build dir> <python> <work dir>
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
build=$1 python=$2 work=$3
tool="$(cd "$(dirname "$0")/../.." && pwd)/tools/reproduce-check"
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# expect <exit status> <pattern> <log> : the check's exit status and a line of its report
expect() {
  local status=$1 pattern=$2 log=$3 actual
  actual=$(cat "$log.rc")
  if [[ $actual != "$status" ]]; then fail "$log: exit status $actual, expected $status"; fi
  if ! grep -Eq -- "$pattern" "$log"; then fail "$log: no line matching '$pattern'"; fi
}
check() {  # check <log> <archive> <options...>
  local log=$1; shift
  "$python" "$tool" "$@" > "$log" 2>&1; echo $? > "$log.rc"
  sed 's/^/    /' "$log"
}

echo "== 1. archive Fig. 3"
cmake --build "$build" --target archive_fig3 || { echo "FAIL: archive_fig3"; exit 1; }
archive=$(ls -t "$build"/shockgas-*-fig3.tar.gz | head -n 1)
name=$(basename "$archive" .tar.gz)
tar tzvf "$archive"

echo "== 2. the untouched archive reproduces (fresh checkout and build)"
check "$work/good.log" "$archive" --work-dir "$work/good"
expect 0 "^result +REPRODUCED" "$work/good.log"
expect 0 "^OK +build/paper_targets/quick/fig3/worldlines.h5 +\(bit-identical" "$work/good.log"
# Later checks compare with this rerun instead of rebuilding.
again=(--compare-with "$work/good/build" --source "$work/good/source")

# alter <label> <python code run in the unpacked archive's directory> ; sets $copy
alter() {
  local label=$1 code=$2
  rm -rf "$work/$label" && mkdir -p "$work/$label" && tar xzf "$archive" -C "$work/$label"
  (cd "$work/$label/$name" && "$python" -c "$code") || fail "altering $label"
  copy="$work/$label.tar.gz"
  tar czf "$copy" -C "$work/$label" "$name"
}
rehash='
import hashlib, json
m = json.load(open("MANIFEST"))
for e in m["files"]:
    if e["archived"]:
        e["sha256"] = hashlib.sha256(open(e["path"], "rb").read()).hexdigest()
json.dump(m, open("MANIFEST", "w"), indent=1)
'
one_number='
import h5py
with h5py.File("build/paper_targets/quick/fig3/worldlines.h5", "r+") as f:
    f["/snapshots/010/velocity"][3] += 1e-15
'

echo "== 3a. one number altered, MANIFEST untouched: the archive's own SHA-256 check names the file"
alter number "$one_number"
check "$work/number.log" "$copy" "${again[@]}" --work-dir "$work/number.work"
expect 1 "^DIFFERENT +build/paper_targets/quick/fig3/worldlines.h5 +\(sha256 differs from MANIFEST" "$work/number.log"
expect 1 "^result +NOT REPRODUCED" "$work/number.log"

echo "== 3b. the same number altered and MANIFEST rehashed: the comparison with the rerun names file and dataset"
alter number-rehashed "$one_number
$rehash"
check "$work/number-rehashed.log" "$copy" "${again[@]}" --work-dir "$work/number-rehashed.work"
expect 1 "^DIFFERENT +build/paper_targets/quick/fig3/worldlines.h5 +\(dataset /snapshots/010/velocity differs: 1 of 500 elements" \
  "$work/number-rehashed.log"
expect 1 "^OK +build/figures/quick/fig3.png" "$work/number-rehashed.log"

echo "== 3c. a file removed and a foreign file added"
alter missing-foreign '
import os
os.remove("build/paper_targets/quick/fig3/worldlines.dat")
open("build/paper_targets/quick/fig3/notes.txt", "w").write("not part of the run\n")
'
check "$work/missing-foreign.log" "$copy" "${again[@]}" --work-dir "$work/missing-foreign.work"
expect 1 "^MISSING +build/paper_targets/quick/fig3/worldlines.dat" "$work/missing-foreign.log"
expect 1 "^FOREIGN +build/paper_targets/quick/fig3/notes.txt" "$work/missing-foreign.log"

echo "== 4. another code version recorded in the archive"
# The archive says another version made it: MANIFEST and the run's own attribute.
another_version='
import json, h5py
m = json.load(open("MANIFEST"))
m["version"] = "v0.0-1-gdeadbee"
json.dump(m, open("MANIFEST", "w"), indent=1)
with h5py.File("build/paper_targets/quick/fig3/worldlines.h5", "r+") as f:
    f.attrs["version"] = "v0.0-1-gdeadbee"
'
# Another simulator (another version and simulator_sha256): the same numbers, but another code.
alter version "$another_version"'
with h5py.File("build/paper_targets/quick/fig3/worldlines.h5", "r+") as f:
    f.attrs["simulator_sha256"] = "0" * 64
'"$rehash"
check "$work/version.log" "$copy" "${again[@]}" --work-dir "$work/version.work"
expect 1 "^code +archive v0.0-1-gdeadbee, rerun .*: DIFFERENT CODE VERSION" "$work/version.log"
expect 1 "worldlines.h5 +\(bit-identical datasets and attributes; made by v0.0-1-gdeadbee, rerun by " "$work/version.log"
# Another version of the same simulator (the same simulator_sha256: a commit outside sim/) made the
# same file: reproduced (the simulator's hash decides, not the version alone).
alter same_simulator "$another_version$rehash"
check "$work/same_simulator.log" "$copy" "${again[@]}" --work-dir "$work/same_simulator.work"
expect 0 "^code +archive v0.0-1-gdeadbee, rerun .*: same simulator" "$work/same_simulator.log"

if ((failures)); then echo "$failures check(s) failed"; exit 1; fi
echo "all archive checks passed"
