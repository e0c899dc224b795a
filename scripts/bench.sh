#!/usr/bin/env bash
# Builds the release flavour and runs every benchmark in full; each prints a
# table (docs/benchmarks.md says what each measures). bench_verifier runs
# without --quick, so its 32-robot relay cases make this take several minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh >/dev/null
bash scripts/build.sh release >/dev/null
for b in build/release/bin/bench_*; do
  echo "== $(basename "$b")"
  "$b"
done
