#!/usr/bin/env bash
# A private single-node Slurm on this machine (Debian's slurm-wlm and munge), for trying the Slurm scripts
# without a cluster; the test `eval_shards_slurm` uses it. It needs root (the daemons run as root here).
#   slurm_local.sh check             exit 0 when it can run here (packages installed, root, 2 cores)
#   slurm_local.sh run DIR CMD...    start slurmctld and slurmd with their configuration, state and logs in
#                                    the new folder DIR, run CMD with SLURM_CONF pointing there, stop them
#                                    again, and exit with CMD's status
# Measured on the 2-core Debian 12 development machine: the daemons answer 3 s after the start.
set -euo pipefail
check() {
  for tool in munged slurmctld slurmd sbatch sinfo; do
    command -v "$tool" >/dev/null || { echo "SKIP: $tool not found (apt-get install slurm-wlm)"; return 1; }
  done
  [ "$(id -u)" -eq 0 ] || { echo "SKIP: a private Slurm needs root here"; return 1; }
  [ "$(nproc)" -ge 2 ] || { echo "SKIP: eval_slurm.sbatch asks for 2 CPUs per task"; return 1; }
}

write_configuration() {
  local dir=$1 host memory
  host=$(hostname -s)
  memory=$(awk '/^MemTotal/ { print int($2 / 1024) }' /proc/meminfo)
  cat >"$dir/slurm.conf" <<CONF
ClusterName=partreg-local
SlurmctldHost=$host
AuthType=auth/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=${SLURM_LOCAL_PORT:-16817}
SlurmdPort=$(( ${SLURM_LOCAL_PORT:-16817} + 1 ))
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
# A job whose dependency can no longer be met (a failed shard before the merge) is cancelled, not left
# pending: sbatch --wait on it then returns.
DependencyParameters=kill_invalid_depend
MpiDefault=none
NodeName=$host CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

# Stops the daemons and waits until they are gone: slurmctld saves its state as it stops, and a caller that
# removes DIR the moment `run` returns would otherwise race it ("Directory not empty").
stop() {
  local dir=$1 daemon pid waited
  for daemon in slurmd slurmctld munged; do
    [ -s "$dir/$daemon.pid" ] || continue
    pid=$(cat "$dir/$daemon.pid")
    kill "$pid" 2>/dev/null || continue
    for ((waited = 0; waited < 300; waited++)); do  # 30 s, then it is killed outright
      kill -0 "$pid" 2>/dev/null || continue 2
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
  done
}

run() {
  slurm_dir=$1  # global: the EXIT trap stops the daemons after this function has returned
  local dir=$1
  shift
  [ -e "$dir" ] && { echo "$0: $dir exists; give a new folder" >&2; return 2; }
  mkdir -p "$dir/state" "$dir/spool"
  write_configuration "$dir"
  export SLURM_CONF=$dir/slurm.conf
  # munged refuses to start twice; one already running (the system's) serves as well.
  if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    mkdir -p /run/munge && chown munge:munge /run/munge 2>/dev/null || true
    munged --force --pid-file="$dir/munged.pid" 2>/dev/null || { echo "$0: munged did not start" >&2; return 1; }
  fi
  trap 'stop "$slurm_dir"' EXIT
  slurmctld -c && slurmd -c
  local waited=0
  until sinfo -h -o %T 2>/dev/null | grep -q idle; do
    sleep 1
    waited=$((waited + 1))
    [ $waited -lt 60 ] || { echo "$0: Slurm was not up after 60 s; see $dir/*.log" >&2; return 1; }
  done
  echo "Slurm up in ${waited} s (configuration $SLURM_CONF)" >&2
  local status=0
  "$@" || status=$?
  return $status
}

case ${1:-} in
  check) check ;;
  run) [ $# -ge 3 ] || { echo "usage: $0 run DIR COMMAND..." >&2; exit 2; }; shift; run "$@" ;;
  *) echo "usage: $0 check | run DIR COMMAND..." >&2; exit 2 ;;
esac
