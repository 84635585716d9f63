#!/usr/bin/env bash
# scripts/slurm_local.sh for real: the one-node cluster comes up and runs a job array through
# sbatch; `sbatch --wait` returns a failing job's exit code; a cancelled job's processes end; the
# command's status is the script's; every daemon is gone when the script ends — after a failing
# command and after a TERM in the middle of a job; a folder that is not the script's is refused.
# Usage: slurm_local_check.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
cluster="$work/cluster"
slurm_local="$source_dir/scripts/slurm_local.sh"
# the jobs' command lines, this run's own (another run of the check may share the machine)
long_a="sleep 301.$$"
long_b="sleep 302.$$"

passed=0
failed=0
expect() {  # expect WHAT COMMAND...
  local what=$1
  shift
  if "$@"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED: $what"
  fi
}
# the three daemons the script started (their PIDs in daemons.txt), none of them alive
daemons_gone() {
  local name pid count=0
  while read -r name pid; do
    count=$((count + 1))
    if kill -0 "$pid" 2>/dev/null; then
      echo "  $name (PID $pid) still runs"
      return 1
    fi
  done < "$cluster/daemons.txt"
  [ "$count" -eq 3 ] || { echo "  $count daemons listed in $cluster/daemons.txt"; return 1; }
}
# no process runs the command line $1 (a job's, not the sbatch that submitted it)
job_gone() { ! pgrep -fx -- "$1" >/dev/null; }

cat > "$work/task.sh" <<'TASK'
#!/usr/bin/env bash
echo "task $SLURM_ARRAY_TASK_ID of job $SLURM_ARRAY_JOB_ID"
TASK
cat > "$work/fails.sh" <<'TASK'
#!/usr/bin/env bash
exit 3
TASK
chmod +x "$work/task.sh" "$work/fails.sh"

# 1. a job array through sbatch --wait; a failing job's exit code; a cancelled job; the command's
#    own status
cat > "$work/session.sh" <<SESSION
#!/usr/bin/env bash
set -u
# an array, watched in squeue (sbatch --wait polls every few seconds)
array=\$(sbatch --parsable --array=0-3 -o "$work/array_%a.txt" "$work/task.sh") || exit 10
for _ in \$(seq 300); do
  [ -z "\$(squeue -h -j "\$array" -o %i)" ] && break
  sleep 0.1
done
sbatch --wait --quiet -o /dev/null "$work/fails.sh"
echo "\$?" > "$work/failing_status.txt"
job=\$(sbatch --parsable -o /dev/null --wrap "$long_a")
for _ in \$(seq 100); do
  [ "\$(squeue -h -j "\$job" -o %T)" = RUNNING ] && break
  sleep 0.1
done
# RUNNING in squeue comes before the job's process: wait for that too (a loaded machine)
for _ in \$(seq 100); do
  pgrep -fx "$long_a" > /dev/null && break
  sleep 0.1
done
pgrep -fx "$long_a" > /dev/null && echo running > "$work/cancelled.txt"
scancel "\$job"
for _ in \$(seq 100); do
  pgrep -fx "$long_a" > /dev/null || break
  sleep 0.1
done
pgrep -fx "$long_a" > /dev/null || echo ended >> "$work/cancelled.txt"
exit 7
SESSION
chmod +x "$work/session.sh"
set +e
bash "$slurm_local" "$cluster" "$work/session.sh" > "$work/session.log" 2>&1
status=$?
set -e
expect "the script exits with its command's status (7), got $status" [ "$status" -eq 7 ]
for i in 0 1 2 3; do
  expect "array task $i wrote its line" grep -q "^task $i of job" "$work/array_$i.txt"
done
expect "sbatch --wait returns the failing job's exit code 3" \
  [ "$(cat "$work/failing_status.txt" 2>/dev/null)" = 3 ]
expect "a cancelled job's process ran, then ended" \
  [ "$(cat "$work/cancelled.txt" 2>/dev/null | tr '\n' ' ')" = "running ended " ]
expect "every daemon stopped after the command" daemons_gone
if [ "$failed" -gt 0 ]; then
  echo "the session's output:"
  sed 's/^/  /' "$work/session.log"
fi

# 2. a TERM while a job runs: the job and every daemon end, the script exits 143
cat > "$work/long.sh" <<SESSION
#!/usr/bin/env bash
sbatch --wait --quiet -o /dev/null --wrap "$long_b"
SESSION
chmod +x "$work/long.sh"
bash "$slurm_local" "$cluster" "$work/long.sh" > "$work/term.log" 2>&1 &
script=$!
for _ in $(seq 300); do
  pgrep -fx "$long_b" > /dev/null && break
  sleep 0.1
done
expect "the job to be stopped started" pgrep -fx "$long_b" > /dev/null
kill -TERM "$script"
set +e
wait "$script"
status=$?
set -e
expect "a TERM ends the script with 143, got $status" [ "$status" -eq 143 ]
expect "every daemon stopped after a TERM" daemons_gone
expect "the running job's process ended with the cluster" job_gone "$long_b"
expect "the command's sbatch ended with the script" job_gone "sbatch --wait --quiet -o /dev/null --wrap $long_b"

# 3. a folder that is not the script's: refused before anything starts, left as it was
mkdir -p "$work/other"
echo keep > "$work/other/notes.txt"
set +e
bash "$slurm_local" "$work/other" true > "$work/other.log" 2>&1
status=$?
set -e
expect "a folder of something else is refused (exit 2), got $status" [ "$status" -eq 2 ]
expect "the refusal names the folder" grep -q "$work/other is not empty" "$work/other.log"
expect "the folder is left as it was" [ "$(ls -A "$work/other")" = notes.txt ]

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
