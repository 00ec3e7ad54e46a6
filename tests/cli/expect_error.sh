#!/usr/bin/env bash
# expect_error.sh REGEX OUTPUT -- COMMAND...
# Passes when COMMAND exits with a nonzero status below 128 (an error, not a
# crash), prints exactly one line on stderr matching REGEX, and leaves no
# OUTPUT file behind.
set -u
regex=$1 output=$2
shift 3
rm -f "$output"
stderr=$("$@" 2>&1 >/dev/null)
status=$?
fail() { echo "FAIL: $*"; echo "stderr was:"; echo "$stderr"; exit 1; }
[ "$status" -ne 0 ] || fail "exit status 0"
[ "$status" -lt 128 ] || fail "exit status $status (crash or signal)"
[ "$(printf '%s\n' "$stderr" | wc -l)" -eq 1 ] || fail "expected exactly one line on stderr"
printf '%s\n' "$stderr" | grep -Eq -- "$regex" || fail "stderr does not match /$regex/"
[ ! -e "$output" ] || fail "output file $output exists"
ls "$output".tmp.* >/dev/null 2>&1 && fail "temporary file left behind"
echo "ok: $stderr"
