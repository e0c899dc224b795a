#!/usr/bin/env bash
# The project's main job, on simulated hardware (no robot needed), end to end:
#  1. installs what is needed and builds;
#  2. starts p3at_sim serving the two P3-ATs of the Bounding Overwatch example
#     (its hallway world, faster than real time so the ~195 s mission takes
#     about a minute) and checks a robot with p3at_ctl;
#  3. the pre-deployment check on the operator's station: `vipars gate`;
#  4. two mission_exec processes (one per robot) over real LCM (udpm, ttl=0)
#     and real TCP: each verifies the mission, they agree on its content hash
#     through the launch gate, run it, and re-verify at every transition;
#  5. a summary: outcome, mission time, each robot's true distance to its goal
#     (the simulator's ground truth) and the predicted probability;
#  6. the same mission with a Tmax too tight: refused by both robots, and the
#     simulator confirms that neither robot received a single motion command;
#  7. the verifier's prediction against 200 fast-time runs of the whole team.
# Environment: P3AT_DEMO_BIN=DIR uses binaries already built there (skips the
# install and build), P3AT_DEMO_PORT (8101), P3AT_DEMO_LCM_PORT (7667),
# P3AT_DEMO_SPEEDUP (4), P3AT_DEMO_MODELS (examples/bounding_overwatch/models.yaml).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${P3AT_DEMO_BIN:-}" ]; then
  bash scripts/install-deps.sh >/dev/null
  echo "building (release: the five programs the demo runs, not the test suite)…"
  bash scripts/build.sh release p3at_sim p3at_ctl vipars mission_exec p3at_team_key >/dev/null
  bin=build/release/bin
else
  bin="$P3AT_DEMO_BIN"
fi
work="$(mktemp -d /tmp/p3at-demo.XXXXXX)"
port="${P3AT_DEMO_PORT:-8101}"
lcm="udpm://239.255.76.67:${P3AT_DEMO_LCM_PORT:-7667}?ttl=0"
speedup="${P3AT_DEMO_SPEEDUP:-4}"
mission=examples/bounding_overwatch/mission.yaml
world=examples/bounding_overwatch/world.yaml
models="${P3AT_DEMO_MODELS:-examples/bounding_overwatch/models.yaml}"
# The paper's Rmax of 2 m sits in the uncertain region for this mission
# (P(success) about 0.4 < 0.8: NO-GO, docs/bounding-overwatch.md); the
# operator asks for 2.5 m and 205 s. The mission's own Tmax, 200 s, is 1.1 sd
# past the predicted 194.8 +- 4.3 s: the gate decides 1 % stricter than asked
# (198 s, 2.475 m; docs/verifier.md), where P is 0.77 < 0.8, so it says NO-GO
# there; at 205 s it decides at 202.95 s with P 0.965. The NO-GO run then also
# asks for Tmax 150 s, which the ~195 s mission cannot meet.
criteria=(--rmax 2.5 --tmax 205)
too_tight=(--rmax 2.5 --tmax 150)
[ -f "$models" ] || { echo "no robot models at $models (set P3AT_DEMO_MODELS=FILE)"; exit 2; }

pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

start_sim() {  # $1: log/truth name stem
  "$bin/p3at_sim" --port "$port" --world "$world" --speedup "$speedup" --truth-csv "$work/$1.truth.csv" \
    2>"$work/$1.sim.log" &
  sim_pid=$!
  pids+=("$sim_pid")
  for _ in $(seq 200); do grep -q "port=$((port + 1))" "$work/$1.sim.log" 2>/dev/null && break; sleep 0.05; done
  grep -q "port=$((port + 1))" "$work/$1.sim.log" || { echo "p3at_sim did not start:"; cat "$work/$1.sim.log"; exit 1; }
}
stop_sim() { kill -TERM "$sim_pid"; wait "$sim_pid" 2>/dev/null || true; }

run_team() {  # $1: name stem; the rest: extra mission_exec flags. Sets rc1, rc2.
  local stem=$1; shift
  for r in 1 2; do
    "$bin/mission_exec" --robot "robot$r" --mission "$mission" --models "$models" --team-key "$work/team.key" \
      --hal "tcp://127.0.0.1:$((port + r - 1))" --lcm "$lcm" --gate-timeout 20 "$@" \
      >"$work/$stem.robot$r.out" 2>"$work/$stem.robot$r.log" &
    eval "pid$r=\$!"
    pids+=("$(eval echo "\$pid$r")")
  done
  set +e
  wait "$pid1"; rc1=$?
  wait "$pid2"; rc2=$?
  set -e
}

"$bin/p3at_team_key" "$work/team.key" >/dev/null

echo
echo "== p3at_sim: the Bounding Overwatch hallway, robot1 and robot2 on ports $port and $((port + 1)), ${speedup}x real time"
start_sim go
echo "== p3at_ctl tcp://127.0.0.1:$port status   (is the robot there?)"
"$bin/p3at_ctl" "tcp://127.0.0.1:$port" status

echo
echo "== vipars gate $mission --models $models ${criteria[*]}   (the operator's pre-deployment check)"
set +e
"$bin/vipars" gate "$mission" --models "$models" "${criteria[@]}"
gate_rc=$?
set -e
echo "(exit status $gate_rc: 0 = GO, 1 = NO-GO)"
[ "$gate_rc" -eq 0 ] || { echo "the operator's check says NO-GO: nothing is deployed"; exit 1; }

echo
echo "== two mission_exec processes over real LCM ($lcm) and TCP: launch gate, then the mission"
echo "   (about $((200 / speedup)) s of wall time; logs in $work)"
t0=$(date +%s)
run_team go "${criteria[@]}"
t1=$(date +%s)
stop_sim
grep -h "event=gate-decision\|event=launch" "$work"/go.robot*.log | sed 's/^.*\[mission_exec\] /  /' | cut -c1-160
echo "  … $(cat "$work"/go.robot*.log | grep -c "event=transition") FSA transitions, $(cat "$work"/go.robot*.log | grep -c "event=reverify ") re-verifications"
echo
echo "== summary (exit statuses $rc1 and $rc2, $((t1 - t0)) s of wall time)"
python3 - "$mission" "$work/go.truth.csv" "$work"/go.robot{1,2}.out "$work"/go.robot{1,2}.log <<'PY'
import csv, math, re, sys
mission, truth, outs, logs = sys.argv[1], sys.argv[2], sys.argv[3:5], sys.argv[5:7]
log1 = logs[0]
goals, name = {}, None
for line in open(mission):
    m = re.match(r"\s*- name: (\w+)", line)
    if m: name = m.group(1)
    m = re.match(r"\s*goal: \[([-\d.]+),\s*([-\d.]+)\]", line)
    if m and name and name not in goals: goals[name] = (float(m.group(1)), float(m.group(2)))
last = {}
for row in csv.DictReader(open(truth)):
    last[row["robot"]] = row
def fields(text, event):
    for line in text.splitlines():
        if line.startswith("event=" + event + " "):
            return dict(re.findall(r'(\w+)=("[^"]*"|\S+)', line))
    return {}
summaries = [fields(open(o).read(), "finished") for o in outs]
check = fields(re.sub(r"^.*\] ", "", open(log1).read(), flags=re.M), "gate-check")
outcome = "completed" if all(s.get("outcome") == "finished" for s in summaries) else "NOT completed"
print(f"  outcome:      mission {outcome}")
print(f"  mission time: {max(float(s.get('t_s', 'nan')) for s in summaries):.1f} s "
      f"(controller time; Tmax {check.get('tmax_s')} s)")
for s in summaries:
    r = s.get("robot")
    gx, gy = goals[r]
    tx, ty = float(last[r]["true_x_m"]), float(last[r]["true_y_m"])
    print(f"  {r}:       {s.get('outcome')} at t = {float(s.get('t_s')):.1f} s in {s.get('state')}; true distance to goal "
          f"{math.hypot(tx - gx, ty - gy):.2f} m (Rmax {check.get('rmax_m')} m); it believes "
          f"{math.hypot(float(s.get('x_m')) - gx, float(s.get('y_m')) - gy):.2f} m")
print(f"  predicted:    P(success) = {check.get('p_joint')} (P(t <= Tmax) {check.get('p_time')}, "
      f"P(every r <= Rmax) {check.get('p_radius')}), threshold {check.get('threshold')}; "
      f"gate decision in {check.get('decision_ms')} ms")
t_end = max(float(s.get("t_s", "nan")) for s in summaries)
dists = []
for s in summaries:
    r = s.get("robot")
    dists.append(math.hypot(float(last[r]["true_x_m"]) - goals[r][0], float(last[r]["true_y_m"]) - goals[r][1]))
met = outcome == "completed" and t_end <= float(check["tmax_s"]) and all(d <= float(check["rmax_m"]) for d in dists)
print(f"  criteria:     {'met' if met else 'NOT met'} (done by Tmax and every robot within Rmax of its goal, true positions)")
p_joint = float(check.get("p_joint", "nan"))
print(f"                one run is one draw: at P(success) {p_joint:.2f} about {100 * (1 - p_joint):.0f} runs in 100 miss"
      f" the criteria (bash scripts/hil-trials.sh 12 runs twelve; the fast-time comparison is below)")
reverify = []
for log in logs:
    for line in open(log):
        if "event=reverify " in line:
            f = dict(re.findall(r"(\w+)=(\S+)", line.split("] ", 1)[1]))
            reverify.append((float(f["t_s"]), f["robot"], float(f["p_joint"])))
if reverify:
    low = min(reverify, key=lambda x: x[2])
    print(f"  re-verified:  {len(reverify)} times during the mission; lowest P(success) {low[2]:.4f} "
          f"({low[1]} at t = {low[0]:.1f} s); at the end {summaries[0].get('p_now')} (robot1), "
          f"{summaries[1].get('p_now')} (robot2)")
PY
[ "$rc1" -eq 0 ] && [ "$rc2" -eq 0 ] || { echo "the mission did not complete: see $work"; exit 1; }

echo
echo "== the same mission with ${too_tight[*]}: both robots verify, refuse, and nothing moves"
start_sim nogo
run_team nogo "${too_tight[@]}"
stop_sim
for r in 1 2; do
  echo "-- robot$r (exit status $(eval echo "\$rc$r"): 4 = NO-GO)"
  grep "event=gate-refused" "$work/nogo.robot$r.out" | cut -c1-200
done
echo "-- robot2's printed refusal:"
sed -n '1,/decision time/p' "$work/nogo.robot2.out" | sed 's/^/   /'
echo "-- the simulator: motion commands each robot received"
grep "stats robot=" "$work/nogo.sim.log" | sed 's/.*stats robot=\([a-z0-9]*\).*\(motion_commands=[0-9]*\).*/   \1 \2/'
[ "$rc1" -eq 4 ] && [ "$rc2" -eq 4 ] || { echo "expected both robots to refuse (exit 4): see $work"; exit 1; }

echo
echo "== the verifier's prediction against 200 fast-time runs of the whole team (vipars simulate)"
"$bin/vipars" simulate "$mission" --world "$world" --runs 200 --csv "$work/bounding_overwatch.csv" | tail -n 4
echo "one row per run: $work/bounding_overwatch.csv; every log: $work"
