#!/usr/bin/env bash
# Measures max |verify - validate| (time curve, radius curve, joint surface) on
# the issue-12 missions of this folder: 1,000 validation runs each, vipars
# report's three maxima. These are the measured errors in
# verifier/include/p3at/verifier/approximation_table.hpp. About 8 minutes on one
# core. Usage: tests/data/honest/measure.sh [OUT_DIR] (from the repository root,
# with build/release/bin on PATH).
set -euo pipefail
out="${1:-/tmp/honest_report}"
while read -r m tmax rmax; do
  d=tests/data/honest/$m
  echo "== $m"
  vipars report "$d/mission.yaml" --models "$d/models.yaml" --world "$d/world.yaml" --trials 1000 --jobs 1 --seed 1 \
    --tmax-range "$tmax" --rmax-range "$rmax" --no-plots --out "$out/$m" || true
done <<'MISSIONS'
five_legs 141.4:158.3:0.5 0.02:2.31:0.05
two_speeds 49.9:56.9:0.5 0.02:1.04:0.02
chain_of_four 48.3:65.0:0.5 0.02:0.82:0.02
z_overwatch 141.6:176.2:0.6 0.02:1.17:0.02
meeting 35.6:42.0:0.5 0.02:0.90:0.02
patrol_recall 37.9:44.7:0.5 0.02:11.37:0.23
MISSIONS
