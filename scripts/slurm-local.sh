#!/usr/bin/env bash
# A one-machine Slurm cluster for trying and testing `renderaudit run --slurm`: munged, slurmctld
# and slurmd on this host, with a minimal slurm.conf and every file under one state directory.
#
#   scripts/slurm-local.sh start [STATE]   installs slurm-wlm and munge if missing, starts the
#                                          daemons, waits until the node is idle, and prints the
#                                          line to export (SLURM_CONF=STATE/slurm.conf)
#   scripts/slurm-local.sh stop  [STATE]   stops them (jobs still running are killed)
#   scripts/slurm-local.sh status [STATE]  sinfo and squeue
#
# STATE defaults to /tmp/renderaudit-slurm. Needs root (the daemons run as root here; a real
# cluster runs them as its own users). Nothing outside STATE is changed but the packages.
set -euo pipefail

action=${1:-}
state=${2:-/tmp/renderaudit-slurm}
case "$action" in start|stop|status) ;; *)
  echo "usage: $0 start|stop|status [STATE_DIR]" >&2; exit 2 ;;
esac

conf=$state/slurm.conf
export SLURM_CONF=$conf

stop_daemons() {
  for pidfile in "$state/slurmd.pid" "$state/slurmctld.pid" "$state/munged.pid"; do
    if [ -s "$pidfile" ] && kill -0 "$(cat "$pidfile")" 2>/dev/null; then
      kill "$(cat "$pidfile")" 2>/dev/null || true
    fi
  done
  # wait (at most 10 s) for them to go, then make sure
  for _ in $(seq 50); do
    alive=0
    for pidfile in "$state/slurmd.pid" "$state/slurmctld.pid" "$state/munged.pid"; do
      [ -s "$pidfile" ] && kill -0 "$(cat "$pidfile")" 2>/dev/null && alive=1
    done
    [ $alive = 0 ] && break
    sleep 0.2
  done
  for pidfile in "$state/slurmd.pid" "$state/slurmctld.pid" "$state/munged.pid"; do
    [ -s "$pidfile" ] && kill -9 "$(cat "$pidfile")" 2>/dev/null || true
    rm -f "$pidfile"
  done
}

if [ "$action" = stop ]; then
  stop_daemons
  echo "slurm-local: stopped ($state)"
  exit 0
fi
if [ "$action" = status ]; then
  sinfo && squeue
  exit 0
fi

if [ "$(id -u)" != 0 ]; then
  echo "slurm-local: needs root to start slurmd (run it with sudo)" >&2
  exit 2
fi
missing=()
for pair in slurmctld:slurmctld slurmd:slurmd sbatch:slurm-client munged:munge; do
  command -v "${pair%%:*}" >/dev/null 2>&1 || PATH=$PATH:/usr/sbin command -v "${pair%%:*}" \
    >/dev/null 2>&1 || missing+=("${pair##*:}")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "slurm-local: installing ${missing[*]} (Debian packages)" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge \
    >"$state.apt.log" 2>&1 || { echo "slurm-local: apt-get failed, see $state.apt.log" >&2; exit 2; }
fi
export PATH=$PATH:/usr/sbin

stop_daemons  # a cluster of an earlier start
mkdir -p "$state/munge" "$state/ctld" "$state/spool"
chmod 0700 "$state/munge"
[ -s "$state/munge.key" ] || mungekey --create --keyfile="$state/munge.key" >/dev/null
chmod 0600 "$state/munge.key"
munged --force --socket="$state/munge/munge.socket" --key-file="$state/munge.key" \
  --pid-file="$state/munged.pid" --log-file="$state/munged.log" --seed-file="$state/munged.seed"

host=$(hostname -s)
cpus=$(nproc)
memory_mb=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
cat >"$conf" <<EOF
# A one-node cluster for renderaudit's tests (scripts/slurm-local.sh).
ClusterName=renderaudit-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$state/munge/munge.socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
# quick turnaround for tests: a cancelled or requeued task's resources come back at once
KillWait=5
MinJobAge=300
SchedulerParameters=sched_interval=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -i -f "$conf"
slurmd -f "$conf"
for _ in $(seq 150); do
  states=$(sinfo -h -o '%T' 2>/dev/null || true)
  if grep -qx idle <<<"$states"; then
    echo "slurm-local: node $host idle ($cpus CPUs); export SLURM_CONF=$conf"
    exit 0
  fi
  sleep 0.2
done
echo "slurm-local: the node did not come up in 30 s; logs: $state/slurmctld.log $state/slurmd.log" >&2
sinfo >&2 || true
exit 1
