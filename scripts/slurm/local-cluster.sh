#!/usr/bin/env bash
# A one-node Slurm cluster on this machine (localhost), for the Slurm test and
# the scaling measurement; not needed on a real cluster.
#
#   scripts/slurm/local-cluster.sh start STATE_DIR   # installs Slurm + munge if missing
#   export SLURM_CONF=STATE_DIR/slurm.conf          # then sbatch, squeue, sinfo work
#   scripts/slurm/local-cluster.sh stop STATE_DIR
#
# Debian's packages (slurmctld, slurmd, slurm-client, munge), no cgroups
# (proctrack/linuxproc, task/none), no accounting database, SlurmUser=root,
# every state and log file under STATE_DIR, addresses on 127.0.0.1 only.
# `start` fails loudly (exit 1 and the daemons' logs) if the node does not
# come up idle within a minute.
set -euo pipefail

usage() {
  echo "usage: $0 start|stop STATE_DIR" >&2
  exit 2
}
[ $# -eq 2 ] || usage
cmd=$1
state=$(mkdir -p "$2" && cd "$2" && pwd)
conf=$state/slurm.conf

die() {
  echo "local-cluster: SLURM COULD NOT START: $*" >&2
  for log in "$state"/slurmctld.log "$state"/slurmd.log /var/log/munge/munged.log; do
    if [ -f "$log" ]; then
      echo "----- last lines of $log" >&2
      tail -n 30 "$log" >&2
    fi
  done
  exit 1
}

install_packages() {
  local need=()
  for bin in slurmctld slurmd sbatch munged; do
    command -v "$bin" >/dev/null || need=(slurmctld slurmd slurm-client munge)
  done
  if [ ${#need[@]} -gt 0 ]; then
    echo "local-cluster: installing ${need[*]} from Debian's packages"
    if [ "$(id -u)" != 0 ]; then
      die "Slurm is not installed and this is not root: apt-get install ${need[*]}"
    fi
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq || die "apt-get update failed"
    apt-get install -y -qq "${need[@]}" >/dev/null || die "apt-get install ${need[*]} failed"
  fi
}

munge_works() {
  munge -n 2>/dev/null | unmunge >/dev/null 2>&1
}

start_munge() {
  if munge_works; then
    return 0 # a munged is already running (the machine's own): use it
  fi
  [ -f /etc/munge/munge.key ] || {
    if command -v mungekey >/dev/null; then
      mungekey --create --keyfile=/etc/munge/munge.key
    else
      dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null
    fi
    chown munge:munge /etc/munge/munge.key
    chmod 400 /etc/munge/munge.key
  }
  mkdir -p /run/munge
  chown munge:munge /run/munge
  chmod 755 /run/munge
  # munged runs as the munge user, so its log and pid file stay in its own
  # directories (STATE_DIR may be private to root); the pid is copied into
  # STATE_DIR so that `stop` ends only this munged.
  rm -f /run/munge/munged.pid
  runuser -u munge -- /usr/sbin/munged || die "munged did not start"
  for _ in $(seq 50); do
    [ -s /run/munge/munged.pid ] && break
    sleep 0.1
  done
  cp /run/munge/munged.pid "$state/munged.pid" || die "munged wrote no pid file"
  for _ in $(seq 50); do
    munge_works && return 0
    sleep 0.1
  done
  die "munged runs but munge -n | unmunge fails"
}

write_conf() {
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  # RealMemory must not exceed what slurmd measures, or the node is drained.
  mem=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
  mkdir -p "$state/ctld" "$state/spool"
  cat >"$conf" <<EOF
ClusterName=rtwlocal
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
# A job whose dependency can never be met (a failed array task) is cancelled
# instead of pending forever.
DependencyParameters=kill_invalid_depend
# Keep finished jobs visible to scontrol for a while (no accounting database).
MinJobAge=600
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  install_packages
  start_munge
  write_conf
  export SLURM_CONF=$conf
  # -c: a clean start, no jobs carried over from an earlier cluster in STATE_DIR.
  slurmctld -c -f "$conf" || die "slurmctld did not start"
  slurmd -f "$conf" || die "slurmd did not start"
  local t=0
  until sinfo -h -N -o '%T' 2>/dev/null | grep -qx idle; do
    t=$((t + 1))
    if [ $t -gt 60 ]; then
      sinfo -N -l >&2 || true
      die "the node is not idle after 60 s"
    fi
    sleep 1
  done
  echo "local-cluster: up ($(sinfo -h -N -o '%N %c CPUs %m MB %T')); export SLURM_CONF=$conf"
}

stop_pidfile() {
  local f=$1 pid
  [ -f "$f" ] || return 0
  pid=$(cat "$f")
  if kill "$pid" 2>/dev/null; then
    for _ in $(seq 50); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$f"
}

stop() {
  # Only the daemons this script started (their pid files are in STATE_DIR).
  stop_pidfile "$state/slurmd.pid"
  stop_pidfile "$state/slurmctld.pid"
  stop_pidfile "$state/munged.pid"
  echo "local-cluster: stopped"
}

case $cmd in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
