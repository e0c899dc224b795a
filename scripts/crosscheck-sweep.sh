#!/usr/bin/env bash
# The cross-check sweep (docs/crosscheck.md, "The sweep"): `vipars crosscheck`
# on 200 generated missions (seeds 1001..1200, 1-6 robots) with 4,000
# validation runs each, niced, and its summary table. Long: about 800,000
# fast-time runs of 1-6 robots (hours on a shared 2-core machine). Results in
# build/crosscheck-sweep/ (index.html, crosscheck.json, missions.jsonl as each
# mission ends, summary.txt). Each mission's runs are kept (missions/NAME/runs.part)
# and reused by the next sweep into the same folder: after a verifier change
# the sweep re-verifies and re-scores in minutes instead of re-simulating.
#   scripts/crosscheck-sweep.sh [FIRST:LAST] [RUNS] [OUT]
set -euo pipefail
cd "$(dirname "$0")/.."
seeds="${1:-1001:1200}"
runs="${2:-4000}"
out="${3:-build/crosscheck-sweep}"
bin="${P3AT_BIN:-build/release/bin}"
if [ -z "${P3AT_BIN:-}" ]; then
  bash scripts/build.sh release >/dev/null
fi
start=$(date +%s)
nice -n 10 "$bin/vipars" crosscheck --seeds "$seeds" --runs "$runs" --seed 1 --reuse-runs --out "$out"
echo "sweep: seeds $seeds, $runs runs each, $(( $(date +%s) - start )) s wall; report $out/index.html"
