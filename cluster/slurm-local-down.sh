#!/usr/bin/env bash
# Stops the single-node Slurm that cluster/slurm-local-up.sh DIR started:
# cancels its jobs, stops slurmd, slurmctld and munged by their pid files
# (only the daemons it started), and with --purge removes DIR.
#   bash cluster/slurm-local-down.sh [--purge] [DIR]    # default DIR: /tmp/vipars-slurm
set -uo pipefail
purge=0
if [ "${1:-}" = "--purge" ]; then purge=1; shift; fi
DIR="${1:-${VIPARS_SLURM_DIR:-/tmp/vipars-slurm}}"
export SLURM_CONF="$DIR/slurm.conf"

# Stops the daemons named by these pid files together (each takes a second
# or two to shut down), killing any still up after 5 s.
stop_pidfiles() {
  local pidfile pid pids=()
  for pidfile in "$@"; do
    [ -f "$pidfile" ] || continue
    pid="$(cat "$pidfile")"
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then kill "$pid"; pids+=("$pid"); fi
    rm -f "$pidfile"
  done
  for _ in $(seq 1 50); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ "$alive" = 0 ] && return 0
    sleep 0.1
  done
  for pid in "${pids[@]}"; do
    if kill -0 "$pid" 2>/dev/null; then
      echo "slurm-local-down: process $pid still up after 5 s, killing it" >&2
      kill -9 "$pid" 2>/dev/null || true
    fi
  done
}

if [ -f "$SLURM_CONF" ] && [ -f "$DIR/slurmctld.pid" ]; then
  scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
fi
stop_pidfiles "$DIR/slurmd.pid" "$DIR/slurmctld.pid"
stop_pidfiles "$DIR/munge/munged.pid"  # last: the Slurm daemons authenticate through it until they are down
if [ "$purge" = 1 ]; then
  case "$DIR" in /|"") echo "slurm-local-down: refusing to remove '$DIR'" >&2; exit 1 ;; esac
  rm -rf "$DIR"
fi
echo "slurm-local-down: stopped the local Slurm in $DIR"
