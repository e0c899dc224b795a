#!/usr/bin/env bash
# Hardware-in-the-loop trials of the Bounding Overwatch example: N whole
# missions with the real processes (p3at_sim serving both P3-ATs over TCP,
# two mission_exec over real LCM on the loopback), each with its own simulator
# and NOISE seeds, then the same statistics from fast-time runs (vipars
# simulate) and the verifier's prediction, side by side. This is the check
# that what `vipars validate` measures in fast time is what the robots'
# processes do over the real links.
#   bash scripts/hil-trials.sh [N]        N trials (default 8)
# Environment: P3AT_HIL_BIN=DIR uses binaries already built there (skips the
# install and build), P3AT_HIL_SPEEDUP (8; the mission takes 200/8 s of wall
# time per trial), P3AT_HIL_PORT (9100), P3AT_HIL_LCM_PORT (7800).
# Exit status: 0 when every trial finished, 1 when one did not.
set -euo pipefail
cd "$(dirname "$0")/.."
trials="${1:-8}"
if [ -z "${P3AT_HIL_BIN:-}" ]; then
  bash scripts/install-deps.sh >/dev/null
  echo "building (release)…"
  bash scripts/build.sh release >/dev/null
  bin=build/release/bin
else
  bin="$P3AT_HIL_BIN"
fi
work="$(mktemp -d /tmp/p3at-hil.XXXXXX)"
m=examples/bounding_overwatch
speedup="${P3AT_HIL_SPEEDUP:-8}"
port="${P3AT_HIL_PORT:-9100}"
lcm="udpm://239.255.76.67:${P3AT_HIL_LCM_PORT:-7800}?ttl=0"
criteria=(--rmax 2.5 --tmax 205)  # as scripts/demo.sh: the operator's criteria, a GO for this mission
"$bin/p3at_team_key" "$work/team.key" >/dev/null

pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

echo "== $trials trials over TCP and LCM (p3at_sim at ${speedup}x real time); logs in $work"
printf '%-6s %-10s %-10s %s\n' trial robot1_s team_s outcome
failed=0
for t in $(seq 1 "$trials"); do
  "$bin/p3at_sim" --port "$port" --world "$m/world.yaml" --speedup "$speedup" --seed "$((1000 + t))" \
    2>"$work/sim.$t.log" &
  sim=$!
  pids+=("$sim")
  for _ in $(seq 200); do grep -q "port=$((port + 1))" "$work/sim.$t.log" 2>/dev/null && break; sleep 0.05; done
  for r in 1 2; do
    "$bin/mission_exec" --robot "robot$r" --mission "$m/mission.yaml" --models "$m/models.yaml" \
      --team-key "$work/team.key" --hal "tcp://127.0.0.1:$((port + r - 1))" --lcm "$lcm" \
      --seed "$((2000 + 2 * t + r))" "${criteria[@]}" >"$work/robot$r.$t.out" 2>"$work/robot$r.$t.log" &
    eval "exec$r=\$!"
  done
  rc1=0 rc2=0
  wait "$exec1" || rc1=$?
  wait "$exec2" || rc2=$?
  kill -TERM "$sim" 2>/dev/null || true
  wait "$sim" 2>/dev/null || true
  finish() { grep -ho 'phase=finished t_s=[0-9.]*' "$work/robot$1.$t.log" | head -1 | cut -d= -f3; }
  r1="$(finish 1)" r2="$(finish 2)"
  if [ "$rc1" = 0 ] && [ "$rc2" = 0 ] && [ -n "$r1" ] && [ -n "$r2" ]; then
    printf '%-6s %-10s %-10s finished\n' "$t" "$r1" "$r2"
    echo "$r1 $r2" >>"$work/finish.txt"
  else
    printf '%-6s %-10s %-10s exit statuses %s %s (see %s)\n' "$t" "${r1:--}" "${r2:--}" "$rc1" "$rc2" "$work"
    failed=$((failed + 1))
  fi
done

echo
echo "== the same mission: 300 fast-time runs (vipars simulate) and the verifier"
"$bin/vipars" simulate "$m/mission.yaml" --world "$m/world.yaml" --runs 300 --seed 5000 \
  --csv "$work/fast.csv" >/dev/null
"$bin/vipars" verify "$m/mission.yaml" --models "$m/models.yaml" "${criteria[@]}" --json >"$work/verify.json" || true
python3 - "$work" <<'EOF'
import csv, json, statistics as st, sys
work = sys.argv[1]
def line(name, xs):
    if len(xs) < 2:
        return f"{name:<34} {len(xs):>5}  (too few to summarise)"
    se = st.stdev(xs) / len(xs) ** 0.5
    return f"{name:<34} {len(xs):>5}  {st.mean(xs):8.1f}  {st.stdev(xs):6.1f}  {se:6.1f}"
try:
    hil = [tuple(map(float, l.split())) for l in open(f"{work}/finish.txt")]
except FileNotFoundError:
    hil = []
fast = [r for r in csv.DictReader(open(f"{work}/fast.csv")) if r["outcome"] == "success"]
v = json.load(open(f"{work}/verify.json"))
print(f"{'completion time (s)':<34} {'runs':>5}  {'mean':>8}  {'sd':>6}  {'se':>6}")
print(line("over TCP + LCM (these trials)", [b for _, b in hil]))
print(line("fast time (vipars simulate)", [float(r["time_s"]) for r in fast]))
print(f"{'predicted (vipars verify)':<34} {'-':>5}  {v['completion_mean_s']:8.1f}  {v['completion_sd_s']:6.1f}")
print(line("robot1 done, over TCP + LCM", [a for a, _ in hil]))
EOF
[ "$failed" = 0 ] || { echo "$failed trial(s) did not finish"; exit 1; }
