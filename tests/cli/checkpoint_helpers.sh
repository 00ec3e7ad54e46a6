# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the checkpoint tests (sigkill_resume_test.sh, damaged_checkpoint_test.sh, faults_test.sh).

# run_until_checkpoints COUNT SIGNAL ERRFILE -- COMMAND...
# Starts COMMAND with its stderr in ERRFILE, waits until it has noted COUNT
# checkpoints (or ended), sends it SIGNAL and returns its exit status.
run_until_checkpoints() {
  local count=$1 signal=$2 err=$3
  shift 4
  "$@" 2>"$err" &
  local pid=$!
  for _ in $(seq 1 600); do
    [ "$(grep -c '^shockgas-sim: checkpoint:' "$err")" -ge "$count" ] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.02
  done
  kill -"$signal" "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
}
