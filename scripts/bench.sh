#!/usr/bin/env bash
# Builds the release flavour and runs every benchmark; each prints a table.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh >/dev/null
bash scripts/build.sh release >/dev/null
for b in build/release/bin/bench_*; do
  echo "== $(basename "$b")"
  "$b"
done
