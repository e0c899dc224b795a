#!/usr/bin/env bash
# The project's main job, on simulated hardware (no robot needed):
# installs what is needed, builds, starts the P3-AT firmware emulator, checks
# the robot with p3at_ctl, drives a square and shows the robot's odometry
# against the simulator's ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh >/dev/null
echo "building (release)…"
bash scripts/build.sh release >/dev/null
bin=build/release/bin
work="$(mktemp -d /tmp/p3at-demo.XXXXXX)"
port="${P3AT_DEMO_PORT:-8101}"
side_m="${P3AT_DEMO_SQUARE_M:-2}"

"$bin/p3at_sim" --port "$port" --world examples/worlds/open.yaml --truth-csv "$work/truth.csv" 2>"$work/sim.log" &
sim_pid=$!
trap 'kill $sim_pid 2>/dev/null || true' EXIT
for _ in $(seq 100); do grep -q "port=$port" "$work/sim.log" 2>/dev/null && break; sleep 0.05; done
grep -q "port=$port" "$work/sim.log" || { echo "p3at_sim did not start:"; cat "$work/sim.log"; exit 1; }

echo
echo "== p3at_ctl tcp://127.0.0.1:$port status"
"$bin/p3at_ctl" "tcp://127.0.0.1:$port" status
echo
echo "== p3at_ctl tcp://127.0.0.1:$port drive --square $side_m   (odometry as the robot reports it)"
"$bin/p3at_ctl" "tcp://127.0.0.1:$port" drive --square "$side_m" --print-every 2
sleep 0.3
echo
echo "== where the robot really is (simulator ground truth) against its odometry"
python3 - "$work/truth.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = rows[-1]
tx, ty, tth = float(last["true_x_m"]), float(last["true_y_m"]), float(last["true_theta_rad"])
ox, oy, oth = float(last["odom_x_m"]), float(last["odom_y_m"]), float(last["odom_theta_rad"])
print(f"{'':10}{'x_m':>9}{'y_m':>9}{'th_deg':>9}")
print(f"{'truth':10}{tx:9.3f}{ty:9.3f}{math.degrees(tth):9.2f}")
print(f"{'odometry':10}{ox:9.3f}{oy:9.3f}{math.degrees(oth):9.2f}")
print(f"odometry error: {math.hypot(tx-ox, ty-oy):.3f} m, {math.degrees(math.atan2(math.sin(tth-oth), math.cos(tth-oth))):.2f} deg"
      f" after {float(last['time_s']):.1f} s ({len(rows)} simulator cycles)")
PY
kill -TERM $sim_pid; wait $sim_pid 2>/dev/null || true
echo
echo "simulator log: $work/sim.log (last lines below)"
tail -n 3 "$work/sim.log"

echo
echo "== the seed paper's Bounding Overwatch mission, whole team in fast time (200 runs)"
"$bin/vipars" simulate examples/bounding_overwatch/mission.yaml --world examples/bounding_overwatch/world.yaml \
  --runs 200 --csv "$work/bounding_overwatch.csv" | tail -n 4
echo "one row per run: $work/bounding_overwatch.csv"
