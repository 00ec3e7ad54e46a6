#!/usr/bin/env bash
# analyze_expect_error.sh REGEX "OUTPUT..." -- COMMAND...
# expect_error.sh for a command with several outputs (a results file and data
# files): passes when COMMAND exits with status 2, prints exactly one line on
# stderr matching REGEX, and leaves none of the OUTPUTs (space-separated)
# behind, nor a temporary file of any of them.
# SPDX-License-Identifier: GPL-3.0-or-later
set -u
regex=$1 outputs=$2
shift 3
expect=$(dirname "$0")/expect_error.sh
for output in $outputs; do rm -f "$output"; done
first=${outputs%% *}
"$expect" "$regex" "$first" -- "$@" || exit 1
for output in $outputs; do
  [ ! -e "$output" ] || { echo "FAIL: output file $output exists"; exit 1; }
  ls "$output".tmp.* >/dev/null 2>&1 && { echo "FAIL: temporary file of $output left behind"; exit 1; }
done
exit 0
