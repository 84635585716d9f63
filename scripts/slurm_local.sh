#!/usr/bin/env bash
# A Slurm cluster of one node on this machine, for as long as one command runs: mjarm's Slurm path
# tested for real (docs/slurm_local.md). Usage:
#   scripts/slurm_local.sh WORK COMMAND [ARG...]
# Installs slurm-wlm and munge from Debian if missing, writes a configuration, a munge key and the
# daemons' state, logs and PID files under WORK (made if missing; a folder it made before is
# emptied first, any other folder that is not empty is refused), starts munged,
# slurmctld and slurmd on localhost without systemd, waits until the node takes jobs, runs COMMAND
# with SLURM_CONF set (sbatch, squeue, scancel and sinfo then talk to this cluster), and stops every
# daemon by the PID it wrote when it ends — also on failure or a signal — after cancelling the jobs
# left (their processes would outlive slurmd). Exits with COMMAND's status; 3 when the cluster did
# not come up (the daemons' logs are printed). SLURM_LOCAL_EXTRA_CONF, when set, is appended to
# the configuration (e.g. "MaxArraySize=4"). The daemons run as the user who runs it (root not
# needed: slurmd then runs only that user's jobs, which is all a local sweep submits). Run it under
# `unshare --pid --fork --kill-child` to be sure nothing outlives it.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: scripts/slurm_local.sh WORK COMMAND [ARG...]" >&2
  exit 2
fi
work=$(realpath -m "$1")
shift

# the Debian packages, once
missing=()
for tool in slurmctld slurmd sbatch munged; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "slurm_local: installing slurm-wlm and munge (for ${missing[*]})" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
    slurm-wlm munge >&2
fi

# WORK is emptied only when it is this script's: never a folder of something else, never one whose
# cluster still runs
if [ -d "$work" ] && [ -n "$(ls -A "$work")" ]; then
  if [ ! -f "$work/slurm.conf" ] || ! grep -qx "ClusterName=mjarm-local" "$work/slurm.conf"; then
    echo "slurm_local: $work is not empty and is not a cluster folder of this script; give an" \
      "empty or new folder" >&2
    exit 2
  fi
  while read -r name pid; do
    if kill -0 "$pid" 2>/dev/null; then
      echo "slurm_local: the cluster in $work still runs ($name, PID $pid)" >&2
      exit 2
    fi
  done < <(cat "$work/daemons.txt" 2>/dev/null)
fi
rm -rf "$work"
mkdir -p "$work"/{state,spool,log,munge/key}
# munged refuses a key folder others can read and a socket folder others cannot
chmod 0700 "$work/munge/key"
chmod 0755 "$work/munge"
dd if=/dev/urandom of="$work/munge/key/munge.key" bs=1024 count=1 status=none
chmod 0400 "$work/munge/key/munge.key"

# two free ports for the controller and the node daemon
read -r ctld_port slurmd_port < <(python3 - <<'PYTHON'
import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets:
    s.bind(("127.0.0.1", 0))
print(*(s.getsockname()[1] for s in sockets))
PYTHON
)
# every daemon and client talks to 127.0.0.1, whatever the host name resolves to
host=$(hostname -s)
# the node as slurmd sees it: a configuration that differs from the hardware is refused
node=$(slurmd -C | head -1)
export SLURM_CONF="$work/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=mjarm-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
# several jobs on the node at once, one CPU each (select/linear runs one job at a time); processes
# found through /proc, no cgroups, no accounting
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SchedulerParameters=sched_interval=1
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
# more configuration lines from the caller (a small MaxArraySize, say)
[ -z "${SLURM_LOCAL_EXTRA_CONF:-}" ] || printf '%s\n' "$SLURM_LOCAL_EXTRA_CONF" >> "$SLURM_CONF"

# TERM to each PID given, then KILL to those still running 5 s later
stop_pids() {
  [ $# -gt 0 ] || return 0
  kill "$@" 2>/dev/null || true
  for _ in $(seq 50); do
    local running=0 pid
    for pid in "$@"; do kill -0 "$pid" 2>/dev/null && running=1; done
    [ "$running" -eq 0 ] && return 0
    sleep 0.1
  done
  kill -KILL "$@" 2>/dev/null || true
}

# every daemon started is stopped by its PID, whatever happens from here on
command_pid=""
stop() {
  local status=$?
  trap - EXIT INT TERM
  if [ -n "$command_pid" ]; then
    # the command and what it started (its own process group)
    kill -TERM -- "-$command_pid" 2>/dev/null || true
    wait "$command_pid" 2>/dev/null || true
  fi
  if [ -f "$work/slurmctld.pid" ]; then
    # the jobs' processes, then the jobs cancelled: slurmd ends those processes, and whatever
    # still runs after 10 s is killed
    local job_pids
    job_pids=$(scontrol listpids 2>/dev/null | awk 'NR > 1 { print $1 }' || true)
    squeue -h -o %i 2>/dev/null | xargs -r scancel 2>/dev/null || true
    for _ in $(seq 100); do
      [ -z "$(squeue -h -o %i 2>/dev/null)" ] && [ "$(scontrol listpids 2>/dev/null | wc -l)" -le 1 ] && break
      sleep 0.1
    done
    # shellcheck disable=SC2086  # one PID per word
    [ -z "$job_pids" ] || kill -KILL $job_pids 2>/dev/null || true
  fi
  # the daemons together (each takes about two seconds to go), munge's last: the others
  # authenticate through it on their way out
  local slurm_pids=() munge_pids=() name pid
  while read -r name pid; do
    if [ "$name" = munged ]; then munge_pids+=("$pid"); else slurm_pids+=("$pid"); fi
  done < <(cat "$work/daemons.txt" 2>/dev/null)
  stop_pids "${slurm_pids[@]}"
  stop_pids "${munge_pids[@]}"
  exit "$status"
}
trap stop EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

fail_start() {
  echo "slurm_local: $1; the daemons' logs:" >&2
  for log in "$work"/log/*.log "$work"/munge/munged.log; do
    [ -f "$log" ] && { echo "== $log" >&2; tail -20 "$log" >&2; }
  done
  exit 3
}

# start NAME PID_FILE COMMAND...: runs a daemon and adds its PID to daemons.txt, which keeps it
# after the daemon removes its PID file on the way out
start() {
  local name=$1 pid_file=$2
  shift 2
  "$@" || fail_start "$name did not start"
  for _ in $(seq 50); do
    [ -s "$pid_file" ] && break
    sleep 0.1
  done
  [ -s "$pid_file" ] || fail_start "$name wrote no PID file ($pid_file)"
  echo "$name $(cat "$pid_file")" >> "$work/daemons.txt"
}
start munged "$work/munge/munged.pid" munged --force --socket="$work/munge/munge.socket" \
  --key-file="$work/munge/key/munge.key" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed"
start slurmctld "$work/slurmctld.pid" slurmctld -f "$SLURM_CONF"
start slurmd "$work/slurmd.pid" slurmd -f "$SLURM_CONF"
# the node takes jobs once it is idle (about a second)
for _ in $(seq 300); do
  state=$(sinfo -h -N -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.1
done
[ "${state:-}" = idle ] || fail_start "the node is '${state:-unknown}' after 30 s, not idle"

# in the background, so that a signal to this script is handled at once, not when it ends, and in
# a process group of its own, so that what it starts is stopped with it
set -m
"$@" &
command_pid=$!
set +m
set +e
wait "$command_pid"
status=$?
set -e
command_pid=""
exit "$status"
