#!/bin/bash
# A one-node Slurm cluster on localhost for tests/test_slurm.cpp, every file of it in DIR:
#   one_node_cluster.sh start DIR   writes DIR/slurm.conf, starts slurmctld and slurmd (and
#                                   munged, where auth/none is not there) as the current user,
#                                   and waits until the node is idle; exit 0 when it is.
#                                   Exit 77 when the cluster cannot start, with the reason on
#                                   stdout (the test then skips); the daemons started are
#                                   stopped again before.
#   one_node_cluster.sh stop DIR    stops what start started (by the process ids it wrote).
# Clients (sbatch, squeue) find the cluster with SLURM_CONF=DIR/slurm.conf. Every wait is bounded.
set -u
cmd=${1:-} dir=${2:-}
if [ -z "$cmd" ] || [ -z "$dir" ]; then
  echo "usage: $0 start|stop DIR" >&2
  exit 2
fi

stop() {
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.started-pid" ] || continue
    pid=$(cat "$dir/$name.started-pid")
    kill -TERM "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
    rm -f "$dir/$name.started-pid"
  done
}

cannot() {  # the reason, the last lines of the logs, then stop and skip
  echo "one-node Slurm cluster cannot start: $1"
  for log in "$dir"/log/*; do [ -s "$log" ] && { echo "--- $log"; tail -n 5 "$log"; }; done
  stop
  exit 77
}

# Two TCP ports free on localhost (the controller's and the node daemon's).
free_ports() {
  /usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(" ".join(str(x.getsockname()[1]) for x in s))'
}

if [ "$cmd" = stop ]; then
  stop
  exit 0
fi
[ "$cmd" = start ] || { echo "unknown command $cmd" >&2; exit 2; }

for tool in slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" >/dev/null 2>&1 || PATH=$PATH:/usr/sbin
  command -v "$tool" >/dev/null 2>&1 || cannot "$tool is not installed (Debian: apt-get install slurm-wlm munge)"
done
mkdir -p "$dir/state" "$dir/spool" "$dir/log" || cannot "cannot write $dir"
user=$(id -un)
read -r ctld_port slurmd_port < <(free_ports) || cannot "no free TCP port on localhost"
plugins=$(dirname "$(ldconfig -p | awk '/libslurmfull/ {print $NF; exit}')")/slurm-wlm
[ -d "$plugins" ] || plugins=/usr/lib/x86_64-linux-gnu/slurm-wlm

# auth/none where this Slurm still has it (22.05, Debian 12); else munge with a key of our own
# (BIMLOC_SLURM_AUTH=munge: munge all the same).
if [ -e "$plugins/auth_none.so" ] && [ "${BIMLOC_SLURM_AUTH:-}" != munge ]; then
  auth="AuthType=auth/none
CredType=cred/none"
else
  command -v munged >/dev/null 2>&1 || PATH=$PATH:/usr/sbin
  command -v munged >/dev/null 2>&1 || cannot "no auth/none plugin and munged is not installed"
  dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 2>/dev/null && chmod 600 "$dir/munge.key"
  munged --force --foreground --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge.seed" >"$dir/log/munged.out" 2>&1 &
  echo $! >"$dir/munged.started-pid"
  for _ in $(seq 50); do [ -S "$dir/munge.socket" ] && break; sleep 0.1; done
  [ -S "$dir/munge.socket" ] || cannot "munged did not start"
  auth="AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket"
fi

# CPUs=2 and 4 GiB: what deploy/slurm/shard.sbatch asks (--cpus-per-task=2, --mem=4G).
cat >"$dir/slurm.conf" <<CONF
ClusterName=bimloctest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
$auth
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=60
NodeName=localhost CPUs=2 RealMemory=4096 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 &
echo $! >"$dir/slurmctld.started-pid"
slurmd -D -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 &
echo $! >"$dir/slurmd.started-pid"
for _ in $(seq 60); do
  state=$(timeout 5 sinfo -h -n localhost -o %T 2>/dev/null)
  [ "$state" = idle ] && exit 0
  kill -0 "$(cat "$dir/slurmctld.started-pid")" 2>/dev/null || cannot "slurmctld exited"
  kill -0 "$(cat "$dir/slurmd.started-pid")" 2>/dev/null || cannot "slurmd exited"
  sleep 0.5
done
cannot "the node is not idle after 30 s (state: ${state:-unknown})"
