#!/usr/bin/env bash
# expect_error.sh REGEX OUTPUT -- COMMAND...
# Passes when COMMAND exits with status 2 (every shockgas program's status for
# bad input; not 1, an internal error, nor >= 128, a crash), prints exactly
# one line on stderr matching REGEX, and leaves no OUTPUT file behind.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
regex=$1 output=$2
shift 3
rm -f "$output"
stderr=$("$@" 2>&1 >/dev/null)
status=$?
fail() { echo "FAIL: $*"; echo "stderr was:"; echo "$stderr"; exit 1; }
[ "$status" -eq 2 ] || fail "exit status $status, expected 2 (bad input)"
[ "$(printf '%s\n' "$stderr" | wc -l)" -eq 1 ] || fail "expected exactly one line on stderr"
printf '%s\n' "$stderr" | grep -Eq -- "$regex" || fail "stderr does not match /$regex/"
[ ! -e "$output" ] || fail "output file $output exists"
ls "$output".tmp.* >/dev/null 2>&1 && fail "temporary file left behind"
echo "ok: $stderr"
