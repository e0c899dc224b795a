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

stop_pidfile() {  # name pidfile
  local pidfile="$2" pid
  [ -f "$pidfile" ] || return 0
  pid="$(cat "$pidfile")"
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
    kill "$pid"
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      echo "slurm-local-down: $1 ($pid) still up after 5 s, killing it" >&2
      kill -9 "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$pidfile"
}

if [ -f "$SLURM_CONF" ] && [ -f "$DIR/slurmctld.pid" ]; then
  scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
fi
stop_pidfile slurmd "$DIR/slurmd.pid"
stop_pidfile slurmctld "$DIR/slurmctld.pid"
stop_pidfile munged "$DIR/munge/munged.pid"
if [ "$purge" = 1 ]; then
  case "$DIR" in /|"") echo "slurm-local-down: refusing to remove '$DIR'" >&2; exit 1 ;; esac
  rm -rf "$DIR"
fi
echo "slurm-local-down: stopped the local Slurm in $DIR"
