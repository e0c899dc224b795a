#!/usr/bin/env bash
# Brings up a real single-node Slurm on this machine from Debian's packages
# (munge, slurmctld, slurmd 22.05), as root, without systemd: every file
# (key, config, state, logs, sockets) under one folder, the daemons started
# directly. Used by the CI test of sharded validation (scripts/test-slurm.sh)
# and by hand to try a campaign script before a real cluster (docs/cluster.md).
#
#   bash cluster/slurm-local-up.sh [DIR]      # default DIR: /tmp/vipars-slurm
#   export SLURM_CONF=DIR/slurm.conf          # then sbatch, squeue, sinfo ... as usual
#   bash cluster/slurm-local-up.sh --print-env [DIR]   # just prints that export line
#
# What a container like this one needs (each found by trying):
#   - no cgroup plugins: proctrack/linuxproc and task/none, job accounting off
#     (the container's cgroup tree is not ours to write);
#   - SlurmUser=root and SlurmdUser=root (CI runs as root; no slurm user setup);
#   - a munge key of our own and munged on our own socket (AuthInfo=socket=),
#     so nothing in /etc/munge or /run/munge is needed or touched;
#   - NodeAddr 127.0.0.1 and the node's real name (slurmd -C) and CPU count.
# Stop it with cluster/slurm-local-down.sh DIR.
set -euo pipefail

print_env_only=0
if [ "${1:-}" = "--print-env" ]; then print_env_only=1; shift; fi
DIR="${1:-${VIPARS_SLURM_DIR:-/tmp/vipars-slurm}}"
if [ "$print_env_only" = 1 ]; then echo "export SLURM_CONF=$DIR/slurm.conf"; exit 0; fi

die() { echo "slurm-local-up: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || die "needs root (SlurmUser=root; CI runs as root)"
for bin in munged mungekey slurmctld slurmd sinfo scontrol; do
  command -v "$bin" >/dev/null || die "$bin not found: bash scripts/install-deps.sh installs munge, slurmctld, slurmd, slurm-client"
done
if [ -f "$DIR/slurmctld.pid" ] && kill -0 "$(cat "$DIR/slurmctld.pid")" 2>/dev/null; then
  die "a local Slurm already runs from $DIR (stop it: bash cluster/slurm-local-down.sh $DIR)"
fi

mkdir -p -m 0755 "$DIR"
chmod 0755 "$DIR"
mkdir -p -m 0700 "$DIR/munge" "$DIR/state" "$DIR/spool"
mkdir -p -m 0755 "$DIR/log"

# ---- munge: a key of our own, on our own socket ----
MUNGE_SOCKET="$DIR/munge/munge.socket"
[ -f "$DIR/munge/munge.key" ] || mungekey --create --keyfile="$DIR/munge/munge.key" >/dev/null
chmod 0600 "$DIR/munge/munge.key"
munged --force --key-file="$DIR/munge/munge.key" --socket="$MUNGE_SOCKET" \
  --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/log/munged.log" \
  --seed-file="$DIR/munge/munged.seed" \
  || die "munged did not start: see $DIR/log/munged.log"

# ---- slurm.conf for this one machine ----
NODE="$(slurmd -C | sed -n 's/^NodeName=\([^ ]*\).*/\1/p')"
CPUS="$(slurmd -C | sed -n 's/.* CPUs=\([0-9]*\).*/\1/p')"
[ -n "$NODE" ] && [ -n "$CPUS" ] || die "slurmd -C did not describe this node"
CTLD_PORT="${VIPARS_SLURMCTLD_PORT:-6817}"
SLURMD_PORT="${VIPARS_SLURMD_PORT:-6818}"
cat > "$DIR/slurm.conf" <<CONF
# Written by cluster/slurm-local-up.sh: a single-node Slurm for tests.
ClusterName=vipars-local
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
# No cgroups in a container: track processes by /proc, no task binding.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=3600
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=local Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$DIR/slurm.conf"

# ---- the daemons (they fork into the background themselves) ----
slurmctld -i || die "slurmctld did not start: see $DIR/log/slurmctld.log"
slurmd || die "slurmd did not start: see $DIR/log/slurmd.log"

# Ready when the node is idle (it registers within a few seconds).
for _ in $(seq 1 60); do
  state="$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)"
  if [ "$state" = "idle" ] || [ "$state" = "mixed" ] || [ "$state" = "allocated" ]; then
    echo "slurm-local-up: node $NODE ($CPUS CPUs) $state; export SLURM_CONF=$DIR/slurm.conf"
    exit 0
  fi
  sleep 0.5
done
echo "slurm-local-up: node not ready after 30 s (state '${state:-none}'); last log lines:" >&2
tail -n 20 "$DIR/log/slurmctld.log" "$DIR/log/slurmd.log" >&2 || true
exit 1
