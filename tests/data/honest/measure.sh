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
# The relay (leg-entered-on-message), 2,000 runs, and the same with NOISE held
# for the whole leg and with 3.5 m legs; then each one's over-confidence when
# decided at Tmax - 0.5 s, Rmax - 0.02 m (the widening, docs/verifier.md).
tmp="$out/missions"
mkdir -p "$tmp"
sed 's/dropoff_m: 0.5}}/dropoff_m: 0.5, noise_persistence_cycles: 1000}}/' examples/relay/mission.yaml > "$tmp/relay_held.yaml"
sed -e 's/goal: \[3.0, 1.0\]/goal: [4.5, 1.0]/' -e 's/goal: \[3.0, 3.0\]/goal: [4.5, 3.0]/' examples/relay/mission.yaml > "$tmp/relay_long.yaml"
for m in examples/relay/mission.yaml:relay:13.5:16.5:0.1 "$tmp/relay_held.yaml:relay_held:13.5:16.5:0.1" \
         "$tmp/relay_long.yaml:relay_long:22:27:0.1"; do
  IFS=: read -r file name t0 t1 dt <<<"$m"
  echo "== $name"
  vipars report "$file" --models tests/sitl/data/relay_models.yaml --world examples/relay/world.yaml --trials 2000 \
    --jobs 1 --seed 1 --tmax-range "$t0:$t1:$dt" --rmax-range 0.1:0.3:0.005 --no-plots --out "$out/$name" || true
  python3 tests/data/honest/shifted_overconfidence.py "$out/$name" 0.5 0.02
done
