// Benchmark of the launch gate's decision (issue #6): what a robot spends,
// before any motion, to decide GO or NO-GO. gate::pre_launch_check() on the
// Bounding Overwatch example reads the mission and models files, hashes them
// (BLAKE2b, with the walls), parses them and verifies the mission; the row
// beside it is verifier::verify() alone on the already-loaded files, so the
// difference is what loading and hashing add. Median and p90 over N calls
// after a warm-up, wall clock and this thread's CPU time side by side (the
// CPU time is what to trust on a busy machine). Target: the whole decision in
// at most 250 ms of CPU on one core, so that a robot's launch is never held up
// by its own gate. Exit status 0 whatever the verdict (a benchmark reports;
// it is not a test), 2 when the example does not load or verify.
// Two more rows: a mission the model cannot vouch for, whose unvouched
// approximations show in its file (tests/data/honest/patrol_recall: a patrol
// loop left on a teammate's message), refused before evaluating, and the same
// mission evaluated as when the operator accepts it (--accept-unvouched): what
// the early refusal saves, side by side.
// Usage: bench_launch_gate [--runs N]   (default 30)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "p3at/common/log.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"

using namespace p3at;

namespace {

constexpr double kTargetCpuMs = 250.0;

double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

double wall_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Samples {
  std::vector<double> wall, cpu;
};

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

void row(const char* what, const Samples& s) {
  std::printf("| %-40s | %8.2f ms | %8.2f ms | %8.2f ms | %8.2f ms |\n", what, quantile(s.wall, 0.5),
              quantile(s.wall, 0.9), quantile(s.cpu, 0.5), quantile(s.cpu, 0.9));
}

/// The rows of a mission refused before evaluating and of the same mission
/// evaluated (accepted); false when it does not behave as that.
bool unvouched_rows(int runs) {
  gate::CheckRequest request;
  const std::string dir = std::string(P3AT_SOURCE_DIR) + "/tests/data/honest/patrol_recall/";
  request.mission_path = dir + "mission.yaml";
  request.models_path = dir + "models.yaml";
  const gate::VerdictSource source = gate::verifier_source();
  Samples refused, evaluated;
  for (const bool accept : {false, true}) {
    request.accept_unvouched = accept;
    Samples& samples = accept ? evaluated : refused;
    for (int i = 0; i <= runs; ++i) {  // the first call is the warm-up
      const double w0 = wall_ms(), c0 = thread_cpu_ms();
      const gate::CheckReport r = gate::pre_launch_check(request, source);
      if (r.refused_before_evaluation == accept || !r.evaluated()) {
        std::fprintf(stderr, "bench_launch_gate: patrol_recall was %s\n",
                     accept ? "not evaluated when accepted" : "not refused before evaluating");
        return false;
      }
      if (i == 0) continue;
      samples.wall.push_back(wall_ms() - w0);
      samples.cpu.push_back(thread_cpu_ms() - c0);
    }
  }
  row("patrol_recall refused before evaluating", refused);
  row("patrol_recall evaluated (accepted)", evaluated);
  std::printf("(patrol_recall: refusing before evaluating takes %.1fx less CPU than evaluating, medians)\n",
              quantile(evaluated.cpu, 0.5) / quantile(refused.cpu, 0.5));
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 30;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_launch_gate [--runs N]\n");
      return 2;
    }
  }
  if (runs < 1) runs = 1;
  log::threshold() = log::Level::warn;  // the verifier's info lines are not the benchmark

  gate::CheckRequest request;
  request.mission_path = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/mission.yaml";
  request.options.rmax_m = 2.5;    // the operator's criteria of scripts/demo.sh: a GO
  request.options.tmax_s = 205.0;
  const gate::VerdictSource source = gate::verifier_source();

  const gate::CheckReport first = gate::pre_launch_check(request, source);  // warm-up, and the files load
  if (!first.verified()) {
    std::fprintf(stderr, "bench_launch_gate: the example does not verify: %s\n", first.error.c_str());
    return 2;
  }

  Samples check, verify_only;
  for (int i = 0; i < runs; ++i) {
    const double w0 = wall_ms(), c0 = thread_cpu_ms();
    const gate::CheckReport r = gate::pre_launch_check(request, source);
    check.wall.push_back(wall_ms() - w0);
    check.cpu.push_back(thread_cpu_ms() - c0);
    if (r.status != first.status) {
      std::fprintf(stderr, "bench_launch_gate: the decision changed between calls\n");
      return 2;
    }
  }
  for (int i = 0; i < runs; ++i) {
    const double w0 = wall_ms(), c0 = thread_cpu_ms();
    const auto r = source(*first.mission, *first.models, request.options, {}, nullptr);
    verify_only.wall.push_back(wall_ms() - w0);
    verify_only.cpu.push_back(thread_cpu_ms() - c0);
    if (!r) return 2;
  }

  std::printf("\nlaunch gate benchmark: examples/bounding_overwatch, Rmax 2.5 m, %d calls each after a warm-up\n",
              runs);
  std::printf("| %-40s | %11s | %11s | %11s | %11s |\n", "case", "wall median", "wall p90", "CPU median", "CPU p90");
  std::printf("|------------------------------------------|-------------|-------------|-------------|-------------|\n");
  row("pre_launch_check (read, hash, verify)", check);
  row("verify() alone (files already loaded)", verify_only);
  if (!unvouched_rows(runs)) return 2;
  const double cpu = quantile(check.cpu, 0.5);
  std::printf("decision: %s, mission hash %s\n", gate::to_string(first.status), first.mission_hash.c_str());
  std::printf("loading and hashing add %.2f ms of CPU (median) to the verifier's %.2f ms\n",
              cpu - quantile(verify_only.cpu, 0.5), quantile(verify_only.cpu, 0.5));
  std::printf("%s: the gate's decision, %.2f ms of CPU (median) against the target of %.0f ms (%.1fx under)\n",
              cpu <= kTargetCpuMs ? "PASS" : "FAIL", cpu, kTargetCpuMs, kTargetCpuMs / cpu);
  return 0;
}
