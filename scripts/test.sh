#!/usr/bin/env bash
# The project's test command: installs what is needed, then builds and runs
# every test. This is what .ci/run calls.
#   1. release build: unit and hardware-in-the-loop (sitl) tests, the accuracy
#      gate (verify against validate, docs/crosscheck.md), then a sharded
#      validation campaign through a real single-node Slurm (root only), then
#      the fault campaign (scripts/fault-campaign.py: 50 faults)
#   2. the same tests under AddressSanitizer + UndefinedBehaviorSanitizer
#   3. libFuzzer targets, each for a bounded time (P3AT_FUZZ_SECONDS, default 20;
#      longer runs locally: P3AT_FUZZ_SECONDS=600 bash scripts/test.sh)
#   4. SocketCAN tests inside a user-mode Linux kernel with vcan
#   5. serial tests inside a QEMU guest whose /dev/ttyS0 is a real 8250 UART
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# Each stage's heading says when it began (time since the script started), so
# a CI log shows where its minutes go: grep '^====' LOG.
step() { printf '\n==== %s (at %dm%02ds) ====\n' "$*" $((SECONDS / 60)) $((SECONDS % 60)); }

step "release build"
bash scripts/build.sh release
step "release tests (unit, sitl, accuracy)"
ctest --test-dir build/release -L 'unit|sitl|accuracy' --output-on-failure -j "$jobs"
step "sharded validation on a local Slurm (about 40 s)"
bash scripts/test-slurm.sh build/release/bin

step "fault campaign: 50 faults on real processes, $jobs at a time (about 2 min; the seed is printed)"
python3 scripts/fault-campaign.py --bin build/release/bin --faults 50 --jobs "$jobs"

step "sanitizer build (ASan + UBSan)"
bash scripts/build.sh asan
step "sanitizer tests (unit, sitl)"
ctest --test-dir build/asan -L 'unit|sitl' --output-on-failure -j "$jobs"

step "fuzz targets (bounded)"
bash scripts/build.sh fuzz
ctest --test-dir build/fuzz -L fuzz --output-on-failure -j "$jobs"

if [ -x scripts/run-socketcan-tests.sh ]; then
  step "SocketCAN tests inside user-mode Linux"
  bash scripts/run-socketcan-tests.sh build/release
fi
if [ -x scripts/run-serial-tests.sh ]; then
  step "serial tests inside QEMU (8250 UART wired to p3at_sim)"
  bash scripts/run-serial-tests.sh build/release
fi
step "all test stages passed"
