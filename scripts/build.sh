#!/usr/bin/env bash
# Configures and builds one flavour of the project into build/<flavour>.
#   scripts/build.sh release [TARGET...]   optimised, -O2, no debug info (default);
#                                          with targets, only those (and what they link)
#   scripts/build.sh asan      AddressSanitizer + UndefinedBehaviorSanitizer (clang)
#   scripts/build.sh fuzz      clang + libFuzzer targets
set -euo pipefail
cd "$(dirname "$0")/.."
flavour="${1:-release}"
shift || true
jobs="$(nproc)"
case "$flavour" in
  # Optimised, without debug info: it builds in about half the time on 2 cores.
  release) cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" ;;
  # -O0: the sanitized build compiles in two thirds of -O1's time (header-only CLI11
  # alone costs 25 s per file at -O1 with ASan); CI's time limit is on the sum of
  # build and tests. The few libraries the tests spend their time in are -O1
  # all the same (p3at_optimise_when_sanitized, cmake/Sanitizers.cmake: about
  # ten times faster there). -g1 (line tables) is enough for ASan's stack traces.
  # clang, not GCC: the same sanitized tree compiles in about half the CPU time
  # (66 objects: 93 s against GCC's 177 s; the whole build 8.4 min against 14.5
  # on 2 cores), and a second compiler's warnings (-Werror) come with it. The
  # release build stays GCC's.
  # In batches of eight files per translation unit (CMAKE_UNITY_BUILD): the heavy
  # headers are parsed once per batch (cmake/UnityBuild.cmake says why only here,
  # and which files compile on their own).
  asan)    CXX=clang++ cmake -S . -B build/asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g1" \
             -DP3AT_SANITIZE=ON -DP3AT_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON ;;
  # -O1 with line tables only, as OSS-Fuzz builds fuzzers: a quarter less compile
  # time than -O2 -g on the Eigen-heavy verifier sources, stack traces intact.
  fuzz)    CXX=clang++ cmake -S . -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DP3AT_FUZZ=ON \
             -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
             -DP3AT_BUILD_BENCH=OFF -DP3AT_FUZZ_SECONDS="${P3AT_FUZZ_SECONDS:-20}" ;;
  *) echo "usage: scripts/build.sh [release|asan|fuzz] [TARGET...]" >&2; exit 2 ;;
esac
if [ "$flavour" = fuzz ]; then
  # Only the fuzzers: the rest of the tree is built and tested by the other flavours.
  targets=$(sed -n 's/^p3at_add_fuzzer(\([a-z_]*\).*/\1/p' tests/fuzz/CMakeLists.txt)
  cmake --build "build/$flavour" -j "$jobs" --target $targets
elif [ $# -gt 0 ]; then
  cmake --build "build/$flavour" -j "$jobs" --target "$@"
else
  cmake --build "build/$flavour" -j "$jobs"
fi
