#!/usr/bin/env bash
# Builds the release flavour and runs every benchmark in full; each prints a
# table (docs/benchmarks.md says what each measures). bench_verifier runs
# without --quick, so its 32-robot relay cases make this take several minutes.
# bench_verify_vs_validate (docs/benchmarks.md) adds about ten seconds: 400
# Bounding Overwatch runs against verify() on the 51 x 41 grid.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh >/dev/null
bash scripts/build.sh release >/dev/null
for b in build/release/bin/bench_*; do
  echo "== $(basename "$b")"
  "$b"
done
