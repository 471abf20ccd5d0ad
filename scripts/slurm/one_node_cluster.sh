#!/usr/bin/env bash
# A throw-away one-node Slurm cluster on this machine, for trying the job scripts here and
# for the tests: MUNGE, slurmctld and slurmd from Debian's munge and slurm-wlm packages, all
# state, logs and sockets under DIR, nothing in /etc. Needs root (slurmd starts jobs as
# their users).
#
#   one_node_cluster.sh start DIR   writes DIR/slurm.conf, starts the daemons, waits for the
#                                   node to be idle; then: export SLURM_CONF=DIR/slurm.conf
#   one_node_cluster.sh stop DIR    stops them (safe to run twice, or after a failed start)
set -euo pipefail
cmd=${1:-} dir=${2:-}
[ -n "$cmd" ] && [ -n "$dir" ] || { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }

stop() {
    local name pid
    # Jobs still running are cancelled first, so that no job step outlives the daemons.
    if [ -f "$dir/slurmctld.pid" ] && command -v scancel >/dev/null; then
        SLURM_CONF=$dir/slurm.conf scancel --user="$(id -un)" 2>/dev/null || true
        sleep 1
    fi
    for name in slurmd slurmctld munged; do
        [ -f "$dir/$name.pid" ] || continue
        pid=$(cat "$dir/$name.pid")
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
        rm -f "$dir/$name.pid"
    done
}

if [ "$cmd" = stop ]; then stop; exit 0; fi
[ "$cmd" = start ] || { echo "one_node_cluster.sh: unknown command '$cmd' (start or stop)" >&2; exit 2; }
[ "$(id -u)" -eq 0 ] || { echo "one_node_cluster.sh: needs root" >&2; exit 1; }
for exe in munged slurmctld slurmd sbatch; do
    command -v "$exe" >/dev/null || { echo "one_node_cluster.sh: $exe not found (apt-get install munge slurm-wlm)" >&2; exit 1; }
done
dir=$(mkdir -p "$dir" && cd "$dir" && pwd)
mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
chmod 700 "$dir/munge"

# A free TCP port above 20000 for each daemon.
free_port() {
    local p
    for _ in $(seq 100); do
        p=$((20000 + RANDOM % 20000))
        if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then echo "$p"; return; fi
    done
    echo "one_node_cluster.sh: no free port" >&2
    exit 1
}

host=$(hostname -s)
cpus=$(getconf _NPROCESSORS_ONLN)
mem=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
cat > "$dir/slurm.conf" <<CONF
# One node, this machine; written by scripts/slurm/one_node_cluster.sh.
ClusterName=lighthouse
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# A job whose dependency failed is cancelled rather than left pending.
SchedulerParameters=kill_invalid_depend
ReturnToService=2
SlurmdTimeout=60
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=main Nodes=ALL Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
export SLURM_CONF=$dir/slurm.conf

trap 'stop' ERR
munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 120); do
    state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
    case $state in idle*) echo "one_node_cluster.sh: node $host idle ($cpus CPUs); export SLURM_CONF=$SLURM_CONF"; exit 0 ;; esac
    sleep 0.5
done
echo "one_node_cluster.sh: the node did not come up; see $dir/slurmctld.log and $dir/slurmd.log" >&2
tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
stop
exit 1
