#!/usr/bin/env bash
# CI: a sharded validation campaign through a real single-node Slurm
# (docs/cluster.md). Needs root (SlurmUser=root); CI runs as root.
#   bash scripts/test-slurm.sh [BIN_DIR]     # default build/release/bin
# 1. brings up munge, slurmctld and slurmd (cluster/slurm-local-up.sh);
# 2. runs a 200-run Bounding Overwatch campaign unsharded, then as 4 shards
#    through `sbatch --array` and the dependent merge job, and compares the
#    JSON, the text report and the CSV byte for byte;
# 3. the same campaign with shard 2 killed by scancel: the merge job names
#    the missing shard; rerunning only that shard completes the campaign
#    with the same bytes;
# 4. a 3-mission cross-check campaign as 2 shards by mission: the merged
#    lines and summary byte-identical to the unsharded campaign's.
# About 40 s on the shared 2-core machine (most of it the runs and Slurm's
# scheduling passes); the last line says how long it took.
set -euo pipefail
cd "$(dirname "$0")/.."
start_s=$(date +%s)
bin="${1:-build/release/bin}"
say() { printf 'test-slurm: %s\n' "$*"; }
fail() { say "FAILED: $*" >&2; exit 1; }

if [ "$(id -u)" -ne 0 ]; then
  # Not a pass: said as a skip, and CI (which runs as root) never takes this branch.
  if [ "${CI:-}" = "true" ]; then fail "needs root (CI runs as root)"; fi
  say "SKIPPED: needs root to run slurmctld/slurmd as SlurmUser=root (CI runs as root)"
  exit 0
fi
[ -x "$bin/vipars" ] || fail "$bin/vipars not built"
export VIPARS="$(cd "$bin" && pwd)/vipars"

work="$(mktemp -d /tmp/vipars-slurm-test.XXXXXX)"
slurm_dir="$work/slurm"
# Ports of its own, so a developer's local Slurm on the default ports is left alone.
export VIPARS_SLURMCTLD_PORT="${VIPARS_SLURMCTLD_PORT:-6917}" VIPARS_SLURMD_PORT="${VIPARS_SLURMD_PORT:-6918}"
cleanup() {
  bash cluster/slurm-local-down.sh "$slurm_dir" >/dev/null 2>&1 || true
  if [ "${KEEP_SLURM_TEST:-0}" = 1 ]; then say "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
bash cluster/slurm-local-up.sh "$slurm_dir"
export SLURM_CONF="$slurm_dir/slurm.conf"

# Waits for a job to end; prints its final state.
wait_job() {
  local id="$1" state=""
  for _ in $(seq 1 600); do
    state="$(scontrol show job -o "$id" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1)"
    case "$state" in COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) echo "$state"; return 0 ;; esac
    sleep 0.5
  done
  fail "job $id still '$state' after 300 s"
}
# A task's state; empty when Slurm has no record of it (a pending array task
# cancelled with scancel is dropped from its array, not kept as CANCELLED).
task_state() { scontrol show job -o "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1 || true; }
job_id() { sed -n "s/^$1 //p" <<< "$2"; }

ex=examples/bounding_overwatch
args=("$ex/mission.yaml" --world "$ex/world.yaml" --trials 200 --seed 5
      --tmax-range 186:206:4 --rmax-range 1.8:2.4:0.2)

say "unsharded reference: 200 runs"
"$VIPARS" validate "${args[@]}" --json --csv "$work/whole.csv" > "$work/whole.json"
"$VIPARS" validate "${args[@]}" > "$work/whole.txt" 2>/dev/null

same_result() {  # campaign folder
  cmp "$work/whole.json" "$1/result.json" || fail "$1/result.json differs from the unsharded JSON"
  cmp "$work/whole.txt" "$1/result.txt" || fail "$1/result.txt differs from the unsharded text report"
  cmp "$work/whole.csv" "$1/runs.csv" || fail "$1/runs.csv differs from the unsharded CSV"
}

# ---- 1. four shards, then the merge job ----
say "4 shards through sbatch --array, then the dependent merge job"
jobs="$(bash cluster/validate-campaign.sh submit "$work/c1" 4 -- "${args[@]}")"
array="$(job_id array "$jobs")"; merge="$(job_id merge "$jobs")"
[ "$(wait_job "$merge")" = COMPLETED ] || { cat "$work"/c1/logs/*; fail "merge job $merge did not complete"; }
for i in 0 1 2 3; do
  [ "$(task_state "${array}_$i")" = COMPLETED ] || fail "shard task ${array}_$i did not complete"
  grep -q "shard $i/4 (job vipars-validate ${array}_$i): 50/50 runs" "$work"/c1/logs/shard-$i-*.out ||
    { cat "$work"/c1/logs/shard-$i-*.out; fail "shard $i's log has no progress line with its job and runs done"; }
done
grep -q "merged 200 of 200 runs expected" "$work"/c1/logs/merge-*.out ||
  { cat "$work"/c1/logs/merge-*.out; fail "the merge log does not say runs merged of runs expected"; }
same_result "$work/c1"
say "4 shards: JSON, text and CSV byte-identical to the unsharded campaign"

# ---- 2. one shard killed, merge names it, rerun only it ----
jobs="$(bash cluster/validate-campaign.sh submit "$work/c2" 4 --hold -- "${args[@]}")"
array="$(job_id array "$jobs")"; merge="$(job_id merge "$jobs")"
# Start shard 2 alone and cancel it once Slurm shows it running. A shard of
# 50 runs lasts about a second, so on an idle machine it may end before it
# is seen running; then shard 3, still held, is cancelled before it starts
# (also a shard that never wrote its part). Which one happened is said.
victim=2
scontrol release "${array}_2" >/dev/null 2>&1
seen=""
for _ in $(seq 1 400); do
  state="$(task_state "${array}_2")"
  [ "$state" = "${seen##* }" ] || seen="$seen $state"
  [ "$state" = PENDING ] || break
  sleep 0.02
done
if [ "$state" = RUNNING ] && scancel "${array}_2" 2>/dev/null; then
  killed_while="running"
else
  victim=3
  scancel "${array}_3"
  killed_while="held, before it started (shard 2 went$seen before it could be cancelled running)"
fi
say "shard $victim killed with scancel while $killed_while"
scontrol release "$array" >/dev/null 2>&1 || true
[ "$(wait_job "$merge")" = FAILED ] || { cat "$work"/c2/logs/merge-*.out; fail "merge job $merge should fail"; }
state="$(task_state "${array}_$victim")"
[ "$state" = CANCELLED ] || { [ "$victim" = 3 ] && [ -z "$state" ]; } ||
  fail "shard task ${array}_$victim is $state, not CANCELLED"
[ ! -e "$work/c2/shard-$victim-of-4.part" ] || fail "a cancelled shard left a part"
[ ! -e "$work/c2/result.json" ] || fail "a result was written with a shard missing"
first=$((victim * 50)); last=$((victim * 50 + 49))
merge_log="$(cat "$work"/c2/logs/merge-*.out)"
grep -qF "missing 1 of 4 shards: shard $victim/4 (runs $first..$last); rerun it with --shard $victim/4" <<< "$merge_log" ||
  { echo "$merge_log"; fail "the merge log does not name the missing shard"; }
grep -qF "merged 150 of 200 runs expected" <<< "$merge_log" ||
  { echo "$merge_log"; fail "the merge log does not say runs merged of runs expected"; }
say "the merge job named the missing shard $victim/4; rerunning only that shard"
jobs="$(bash cluster/validate-campaign.sh rerun "$work/c2" "$victim")"
array="$(job_id array "$jobs")"; merge="$(job_id merge "$jobs")"
[ "$(wait_job "$merge")" = COMPLETED ] || { cat "$work"/c2/logs/*; fail "merge job $merge after the rerun did not complete"; }
[ "$(task_state "${array}_$victim")" = COMPLETED ] || fail "the rerun of shard $victim did not complete"
same_result "$work/c2"
say "rerun of shard $victim alone: JSON, text and CSV byte-identical to the unsharded campaign"
# ---- 3. a cross-check campaign sharded by mission ----
say "cross-check of 3 generated missions: unsharded, then 2 shards by mission through sbatch --array"
cc=(crosscheck --seeds 1:3 --robots 1:2 --runs 20 --calibration-runs 4 --no-report)
# The same --out for both (it is in the printed commands): the unsharded run's goes first.
"$VIPARS" "${cc[@]}" --out "$work/cc-out" > "$work/cc-whole.txt" 2>/dev/null
cp "$work/cc-out/summary.txt" "$work/cc-whole-summary.txt"
rm -rf "$work/cc-out"
jobs="$(bash cluster/validate-campaign.sh submit "$work/c3" 2 -- "${cc[@]}" --out "$work/cc-out")"
merge="$(job_id merge "$jobs")"
[ "$(wait_job "$merge")" = COMPLETED ] || { cat "$work"/c3/logs/*; fail "cross-check merge job $merge did not complete"; }
cmp "$work/cc-whole.txt" "$work/c3/result.txt" || fail "merged cross-check lines and summary differ from the unsharded campaign's"
cmp "$work/cc-whole-summary.txt" "$work/cc-out/summary.txt" || fail "merged cross-check summary.txt differs"
say "cross-check by mission: lines, summary and summary.txt byte-identical to the unsharded campaign"
say "passed in $(( $(date +%s) - start_s )) s"
