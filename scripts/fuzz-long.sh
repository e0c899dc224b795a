#!/usr/bin/env bash
# Long libFuzzer runs (issue 14: every fuzzer 10^7 executions or an hour, under
# ASan + UBSan), one fuzzer at a time, each from a fresh copy of its committed
# seed corpus into build/fuzz-long/<fuzzer>/corpus, so every run is reproducible
# from the tree. Not part of CI (CI runs each fuzzer for P3AT_FUZZ_SECONDS).
#
#   scripts/fuzz-long.sh [-r RUNS] [-t SECONDS] [-n NICE] [-o DIR] [FUZZER[:SECONDS] ...]
#     -r RUNS     executions per fuzzer (default 10000000)
#     -t SECONDS  time cap per fuzzer (default 3600); FUZZER:SECONDS overrides it
#     -n NICE     niceness of the fuzzers (default 15: the machine is shared)
#     -o DIR      where the corpora, logs and summary go (default build/fuzz-long);
#                 two runs side by side (one per core) need two directories
#     FUZZER      a target name (fuzz_arcos_decoder, ...); default: all of them
#
# A fuzzer stops at whichever of RUNS or SECONDS comes first, or at its first
# crash (the input is left in build/fuzz-long/<fuzzer>/artifacts/). The table
# at the end (also in build/fuzz-long/summary.txt) gives per fuzzer: executions,
# exec/s, wall seconds, CPU seconds (user+sys of the fuzzer process), final
# coverage (cov = edges, ft = features, corp = corpus units) and crashes
# (inputs left in artifacts/, plus UBSan "runtime error" reports in the log).
# The fuzz build's UBSan checks are recoverable; UBSAN_OPTIONS (as in
# scripts/test.sh) makes the first "runtime error" abort, so it is a crash too.
# Exit status: 0 if no fuzzer found anything, 1 otherwise, 2 on usage errors.
set -euo pipefail
cd "$(dirname "$0")/.."

runs=10000000
seconds=3600
niceness=15
out=build/fuzz-long
while getopts "r:t:n:o:h" opt; do
  case "$opt" in
    r) runs="$OPTARG" ;;
    t) seconds="$OPTARG" ;;
    n) niceness="$OPTARG" ;;
    o) out="$OPTARG" ;;
    *) sed -n '2,/^set -e/p' "$0" | grep '^#' >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))

# Each fuzzer's seed corpus, from tests/fuzz/CMakeLists.txt (the one place it is
# declared): "p3at_add_fuzzer(NAME" followed by "CORPUS <dir>".
declare -A seeds
while read -r name dir; do
  dir="${dir//\$\{CMAKE_CURRENT_SOURCE_DIR\}/tests/fuzz}"
  dir="${dir//\$\{PROJECT_SOURCE_DIR\}/.}"
  seeds[$name]="$dir"
done < <(awk '/^p3at_add_fuzzer\(/ { sub(/^p3at_add_fuzzer\(/, ""); name = $1 }
              /^ *CORPUS / && name != "" { print name, $2; name = "" }' tests/fuzz/CMakeLists.txt)
all=$(awk '/^p3at_add_fuzzer\(/ { sub(/^p3at_add_fuzzer\(/, ""); print $1 }' tests/fuzz/CMakeLists.txt)

selected=("$@")
[ ${#selected[@]} -gt 0 ] || read -r -d '' -a selected <<<"$all" || true
for entry in "${selected[@]}"; do
  if [ -z "${seeds[${entry%%:*}]:-}" ]; then
    echo "fuzz-long: unknown fuzzer '${entry%%:*}' (known: $(echo $all))" >&2
    exit 2
  fi
done

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

# Builds only what changed (the fuzz flavour builds the fuzzers alone).
bash scripts/build.sh fuzz >/dev/null

mkdir -p "$out"
summary="$out/summary.txt"
printf '%-22s %12s %8s %8s %8s %8s %8s %6s %8s\n' \
  fuzzer execs exec/s wall_s cpu_s cov ft corp crashes >"$summary"
found=0
for entry in "${selected[@]}"; do
  name="${entry%%:*}"
  cap="$seconds"
  [ "$entry" = "$name" ] || cap="${entry#*:}"
  dir="$out/$name"
  rm -rf "$dir"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp -r "${seeds[$name]}/." "$dir/corpus/"
  log="$dir/fuzz.log"
  cmd=(nice -n "$niceness" build/fuzz/bin/"$name" -runs="$runs" -max_total_time="$cap"
       -timeout=60 -print_final_stats=1 -artifact_prefix="$dir/artifacts/" "$dir/corpus")
  echo "fuzz-long: ASAN_OPTIONS=$ASAN_OPTIONS UBSAN_OPTIONS=$UBSAN_OPTIONS ${cmd[*]}" | tee "$log"
  status=0
  /usr/bin/time -f 'cpu_seconds %U %S wall_seconds %e' -o "$dir/time.txt" "${cmd[@]}" >>"$log" 2>&1 || status=$?
  final_stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  execs=$(final_stat number_of_executed_units)
  rate=$(final_stat average_exec_per_sec)
  read -r _ user sys _ wall <"$dir/time.txt" || true
  cpu=$(awk -v u="${user:-0}" -v s="${sys:-0}" 'BEGIN { printf "%.0f", u + s }')
  # The last status line ("#N DONE cov: X ft: Y corp: Z/..." or a pulse line).
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(sed -n 's/.*corp: \([0-9]*\).*/\1/p' <<<"$last")
  crashes=$(find "$dir/artifacts" -type f | wc -l)
  ub=$(grep -c 'runtime error:' "$log" || true)
  crashes=$((crashes + ub))
  if [ "$status" -ne 0 ] || [ "$crashes" -ne 0 ]; then
    found=1
    echo "fuzz-long: $name exited $status; artifacts: $(ls "$dir/artifacts")" >&2
  fi
  printf '%-22s %12s %8s %8s %8s %8s %8s %6s %8s\n' "$name" "${execs:-?}" "${rate:-?}" \
    "${wall%.*}" "$cpu" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$crashes" >>"$summary"
done
cat "$summary"
exit "$found"
