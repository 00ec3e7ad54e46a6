#!/usr/bin/env bash
# sigint_test.sh SIM OUTPUT: starts a run far too long to finish, sends SIGINT
# after it has started, and checks that the file is written and says
# status = interrupted (read back with h5dump if present, else strings).
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
sim=$1 output=$2
rm -f "$output" "$output.checkpoint" "$output.checkpoint.previous"  # a fresh run: an earlier run's interrupted checkpoint would refuse it (no --resume)
"$sim" -N 200000 -r 0.9 -d 0.01 -t 1e6 -R 1 -q -o "$output" 2>"$output.stderr" &
pid=$!
sleep 1.5
kill -INT "$pid"
wait "$pid"
status=$?
cat "$output.stderr"
[ "$status" -eq 130 ] || { echo "FAIL: exit status $status, expected 130"; exit 1; }
[ -s "$output" ] || { echo "FAIL: no output file"; exit 1; }
if command -v h5dump >/dev/null; then
  h5dump -a /status "$output" | grep -q '"interrupted"' || { echo "FAIL: status attribute is not interrupted"; exit 1; }
else
  grep -aq interrupted "$output" || { echo "FAIL: status is not interrupted"; exit 1; }
fi
echo "ok: interrupted run written"
