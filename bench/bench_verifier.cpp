// Benchmark of the VIPARS verifier (issue #4: the verifier's speed targets),
// timing the library call verify(mission, models, options) on one thread.
//  1. The Bounding Overwatch example at its one criterion point (Tmax 200 s,
//     Rmax 2 m): median and p90 over 20 runs after a warm-up (target <= 20 ms).
//  2. The same with a 51 x 41 grid: Tmax 170..220 s step 1, Rmax 1.0..3.0 m
//     step 0.05 (target <= 100 ms).
//  3. Scaling on generated relay missions (relay_mission_generator.hpp): k
//     robots x m states each, k = 2..32, m = 4..20. Each case runs in its own
//     forked child so its peak memory (ru_maxrss) is its own; the child reports
//     its times and its peak RSS through a pipe. Target: 32 x 20 in <= 1 s
//     and <= 64 MB peak.
// Times are wall clock and this thread's CPU time side by side (on a busy
// machine the wall clock also counts other processes' time). Ends with one
// PASS/FAIL line per target; the exit status is 0 whatever the verdicts (a
// benchmark reports; it is not a test), 2 for a bad argument or an example
// that does not load or verify. docs/benchmarks.md says how to read it.
// Usage: bench_verifier [--quick]   (--quick: fewer runs, k up to 8; a smoke test)

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "p3at/common/log.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"
#include "relay_mission_generator.hpp"

using namespace p3at;

namespace {

constexpr double kPointTargetMs = 20.0;
constexpr double kGridTargetMs = 100.0;
constexpr double kScaleTargetMs = 1000.0;
constexpr double kScaleTargetMb = 64.0;
constexpr std::size_t kScaleTargetRobots = 32, kScaleTargetStates = 20;

/// This thread's CPU time, ms: unlike the wall clock, it does not count the
/// time other processes had the core, so it stays honest on a busy machine.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

/// Wall and CPU time of one call, ms.
struct Elapsed {
  double wall_ms = 0.0, cpu_ms = 0.0;
};
template <class F>
Elapsed timed(F&& f) {
  const double c0 = thread_cpu_ms();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return {std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
          thread_cpu_ms() - c0};
}

/// Nearest-rank percentile (p in (0, 1]) of the samples.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}
double median(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  std::vector<double> s = v;
  std::sort(s.begin(), s.end());
  const std::size_t n = s.size();
  return n % 2 == 1 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

/// Peak resident set of this process so far, MB (Linux reports ru_maxrss in KiB).
double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

/// Values a, a + step, ..., b (count of them given), rounded to 1e-9 so the
/// axis reads as typed.
std::vector<double> axis(double a, double step, std::size_t count) {
  std::vector<double> v;
  for (std::size_t i = 0; i < count; ++i) v.push_back(std::round((a + step * static_cast<double>(i)) * 1e9) / 1e9);
  return v;
}

/// Slope of log(y) against log(x) by least squares: y grows as x^slope.
double growth_exponent(const std::vector<std::pair<double, double>>& xy) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  double n = 0;
  for (const auto& [x, y] : xy) {
    if (!(x > 0.0) || !(y > 0.0)) continue;
    const double lx = std::log(x), ly = std::log(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, n += 1;
  }
  const double den = n * sxx - sx * sx;
  return n >= 2 && den > 0.0 ? (n * sxy - sx * sy) / den : 0.0;
}

std::string verdict(bool pass) { return pass ? "PASS" : "FAIL"; }

// ------------------------------------------------------- Bounding Overwatch

struct PointTimes {
  std::vector<double> ms, cpu_ms;
  verifier::VerifyResult last;
  std::string error;
};

PointTimes time_verify(const mission::Mission& m, const verifier::Models& models, const verifier::VerifyOptions& options,
                       int runs) {
  PointTimes out;
  for (int i = -1; i < runs; ++i) {  // i = -1: the warm-up, not counted
    std::optional<Result<verifier::VerifyResult>> r;
    const Elapsed e = timed([&] { r.emplace(verifier::verify(m, models, options)); });
    if (!*r) {
      out.error = r->error().message;
      return out;
    }
    if (i >= 0) out.ms.push_back(e.wall_ms), out.cpu_ms.push_back(e.cpu_ms);
    out.last = std::move(**r);
  }
  return out;
}

struct BoVerdicts {
  bool point_pass = false, grid_pass = false;
  double point_ms = 0, point_p90 = 0, point_cpu = 0, grid_ms = 0, grid_p90 = 0, grid_cpu = 0;
  bool ran = false;
};

BoVerdicts bench_bounding_overwatch(int runs) {
  BoVerdicts v;
  const std::string dir = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/";
  mission::Mission bo;
  verifier::Models models;
  try {
    bo = mission::load_mission_file(dir + "mission.yaml");
    models = verifier::load_models_file(dir + "models.yaml");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_verifier: %s\n", e.what());
    return v;
  }
  const verifier::VerifyOptions point;
  verifier::VerifyOptions grid;
  grid.tmax_grid = axis(170.0, 1.0, 51);
  grid.rmax_grid = axis(1.0, 0.05, 41);
  const PointTimes p = time_verify(bo, models, point, runs);
  const PointTimes g = time_verify(bo, models, grid, runs);
  for (const PointTimes* t : {&p, &g}) {
    if (!t->error.empty()) {
      std::fprintf(stderr, "bench_verifier: verify failed on the Bounding Overwatch example: %s\n", t->error.c_str());
      return v;
    }
  }
  v.ran = true;
  v.point_ms = median(p.ms), v.point_p90 = percentile(p.ms, 0.9), v.point_cpu = median(p.cpu_ms);
  v.grid_ms = median(g.ms), v.grid_p90 = percentile(g.ms, 0.9), v.grid_cpu = median(g.cpu_ms);
  v.point_pass = v.point_ms <= kPointTargetMs;
  v.grid_pass = v.grid_ms <= kGridTargetMs;

  std::printf("\nverifier benchmark, parts 1 and 2: %s (examples/bounding_overwatch), verify() on one thread, %d runs "
              "after a warm-up\n",
              bo.name.c_str(), runs);
  std::printf("| case                                         | median    | p90       | min       | CPU median | target | median/target |\n");
  std::printf("|----------------------------------------------|-----------|-----------|-----------|------------|--------|---------------|\n");
  char label[64];
  std::snprintf(label, sizeof label, "one criterion point (Tmax %.0f s, Rmax %.1f m)", p.last.tmax_s, p.last.rmax_m);
  std::printf("| %-44s | %6.2f ms | %6.2f ms | %6.2f ms | %7.2f ms | %3.0f ms | %13.2f |\n", label, v.point_ms,
              v.point_p90, *std::min_element(p.ms.begin(), p.ms.end()), v.point_cpu, kPointTargetMs,
              v.point_ms / kPointTargetMs);
  std::snprintf(label, sizeof label, "%zu x %zu grid (Tmax 170..220, Rmax 1..3)", grid.tmax_grid.size(),
                grid.rmax_grid.size());
  std::printf("| %-44s | %6.2f ms | %6.2f ms | %6.2f ms | %7.2f ms | %3.0f ms | %13.2f |\n", label, v.grid_ms,
              v.grid_p90, *std::min_element(g.ms.begin(), g.ms.end()), v.grid_cpu, kGridTargetMs,
              v.grid_ms / kGridTargetMs);
  std::printf("what was computed: P(success) = %.4f at the point (P(t<=Tmax) %.4f, P(r<=Rmax) %.4f), %zu branches, "
              "%zu subsystems, pruned mass %.2g, blocked mass %.2g; grid of %zu cells, the grid's extra cost %.2f ms "
              "(difference of the CPU medians)\n",
              p.last.p_joint, p.last.p_time, p.last.p_radius, p.last.branches, p.last.subsystems, p.last.pruned_mass,
              p.last.blocked_mass, grid.tmax_grid.size() * grid.rmax_grid.size(), v.grid_cpu - v.point_cpu);
  return v;
}

// ----------------------------------------------------------- relay scaling

constexpr std::size_t kMaxRuns = 10;

/// What a forked child sends back: plain data, written with one write().
struct CaseReport {
  bool ok = false;
  char error[240] = {};
  std::size_t runs = 0;
  double ms[kMaxRuns] = {};      ///< wall
  double cpu_ms[kMaxRuns] = {};  ///< this thread's CPU
  double rss_before_mb = 0.0;  ///< peak RSS after building the mission and models, before verify()
  double rss_peak_mb = 0.0;    ///< peak RSS after every verify()
  double p_joint = 0.0, blocked_mass = 0.0, pruned_mass = 0.0;
  std::size_t branches = 0;
  std::size_t messages = 0;
};

/// Runs in the child: builds the case and times verify() at least once, then
/// again until `max_runs` runs or `budget_ms` of verifying, whichever is first.
CaseReport run_case(std::size_t k, std::size_t m, std::size_t max_runs, double budget_ms) {
  CaseReport rep;
  try {
    const mission::Mission relay = bench::relay_mission(k, m);
    const verifier::Models models = bench::relay_models(relay);
    rep.messages = relay.messages.size();
    rep.rss_before_mb = peak_rss_mb();
    const verifier::VerifyOptions options;
    double total = 0.0;
    while (rep.runs < max_runs && (rep.runs == 0 || total < budget_ms)) {
      std::optional<Result<verifier::VerifyResult>> result;
      const Elapsed e = timed([&] { result.emplace(verifier::verify(relay, models, options)); });
      const Result<verifier::VerifyResult>& r = *result;
      if (!r) {
        std::snprintf(rep.error, sizeof rep.error, "%s", r.error().message.c_str());
        return rep;
      }
      rep.ms[rep.runs] = e.wall_ms;
      rep.cpu_ms[rep.runs] = e.cpu_ms;
      ++rep.runs;
      total += e.wall_ms;
      rep.p_joint = r->p_joint, rep.blocked_mass = r->blocked_mass, rep.pruned_mass = r->pruned_mass;
      rep.branches = r->branches;
    }
    rep.rss_peak_mb = peak_rss_mb();
    rep.ok = true;
  } catch (const std::exception& e) {
    std::snprintf(rep.error, sizeof rep.error, "%s", e.what());
  }
  return rep;
}

/// Forks, runs the case in the child (killed by SIGALRM after `limit_s`), and
/// collects its report, or says why there is none.
CaseReport run_case_in_child(std::size_t k, std::size_t m, std::size_t max_runs, double budget_ms, unsigned limit_s) {
  CaseReport failed;
  int fds[2];
  if (pipe(fds) != 0) {
    std::snprintf(failed.error, sizeof failed.error, "pipe: %s", std::strerror(errno));
    return failed;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    std::snprintf(failed.error, sizeof failed.error, "fork: %s", std::strerror(errno));
    close(fds[0]);
    close(fds[1]);
    return failed;
  }
  if (pid == 0) {
    close(fds[0]);
    alarm(limit_s);
    const CaseReport rep = run_case(k, m, max_runs, budget_ms);
    const ssize_t n = write(fds[1], &rep, sizeof rep);  // under PIPE_BUF: one atomic write
    _exit(n == static_cast<ssize_t>(sizeof rep) ? 0 : 1);
  }
  close(fds[1]);
  CaseReport rep;
  std::size_t got = 0;
  auto* bytes = reinterpret_cast<char*>(&rep);
  while (got < sizeof rep) {
    const ssize_t n = read(fds[0], bytes + got, sizeof rep - got);
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got == sizeof rep) return rep;
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM) {
    std::snprintf(failed.error, sizeof failed.error, "stopped: one verify() took over %u s", limit_s);
  } else if (WIFSIGNALED(status)) {
    std::snprintf(failed.error, sizeof failed.error, "the child died of signal %d (%s)", WTERMSIG(status),
                  strsignal(WTERMSIG(status)));
  } else {
    std::snprintf(failed.error, sizeof failed.error, "the child exited with status %d without a report",
                  WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  }
  return failed;
}

struct ScaleVerdicts {
  bool ran_target = false;
  bool time_pass = false, memory_pass = false;
  double target_ms = 0.0, target_cpu_ms = 0.0, target_mb = 0.0;
  std::string target_error;
};

struct ScaleSettings {
  std::vector<std::size_t> robots, states;
  std::size_t max_runs = kMaxRuns;
  double budget_ms = 3000.0;  ///< per case: no further runs once this much was spent
  unsigned limit_s = 600;     ///< per case: the child is stopped after this
};

ScaleVerdicts bench_relay_scaling(const ScaleSettings& set) {
  std::printf("\nverifier benchmark, part 3: generated relay missions (k robots x m states each, "
              "bench/relay_mission_generator.hpp), verify() at the mission's criterion point on one thread; each case "
              "in its own child process; median of up to %zu runs (no more once %.0f ms were spent; stopped after "
              "%u s)\n",
              set.max_runs, set.budget_ms, set.limit_s);
  std::printf("| k  | m  | k*m | msgs | runs | median      | CPU median  | CPU per k*m | branches | P(success) | "
              "RSS before | peak RSS | verify's RSS |\n");
  std::printf("|----|----|-----|------|------|-------------|-------------|-------------|----------|------------|"
              "------------|----------|--------------|\n");
  ScaleVerdicts v;
  std::vector<std::pair<double, double>> time_xy, memory_xy, time_k, time_m;
  double unit_min = 0.0, unit_max = 0.0;
  std::string unit_min_case, unit_max_case;
  for (const std::size_t k : set.robots) {
    bool over_limit = false;  // a larger m only takes longer: skip it
    for (const std::size_t m : set.states) {
      const std::size_t km = k * m;
      const bool target = k == kScaleTargetRobots && m == kScaleTargetStates;
      if (over_limit) {
        std::printf("| %2zu | %2zu | %3zu | skipped: a smaller m already took over %u s\n", k, m, km, set.limit_s);
        if (target) v.target_error = "skipped: a smaller case already took over the limit";
        continue;
      }
      const CaseReport r = run_case_in_child(k, m, set.max_runs, set.budget_ms, set.limit_s);
      if (!r.ok) {
        std::printf("| %2zu | %2zu | %3zu | %s\n", k, m, km, r.error);
        over_limit = std::strncmp(r.error, "stopped", 7) == 0;
        if (target) v.target_error = r.error;
        continue;
      }
      const double med = median(std::vector<double>(r.ms, r.ms + r.runs));
      const double cpu = median(std::vector<double>(r.cpu_ms, r.cpu_ms + r.runs));
      const double per_unit_us = 1000.0 * cpu / static_cast<double>(km);
      const double grown = r.rss_peak_mb - r.rss_before_mb;
      std::printf("| %2zu | %2zu | %3zu | %4zu | %4zu | %8.1f ms | %8.1f ms | %8.1f us | %8zu | %10.4f | %7.1f MB | "
                  "%5.1f MB | %9.1f MB |\n",
                  k, m, km, r.messages, r.runs, med, cpu, per_unit_us, r.branches, r.p_joint, r.rss_before_mb,
                  r.rss_peak_mb, grown);
      if (r.blocked_mass > 1e-6) {
        std::printf("|    |    |     | blocked mass %.3g: some orderings never finish (a generator or engine bug)\n",
                    r.blocked_mass);
      }
      time_xy.emplace_back(static_cast<double>(km), cpu);
      memory_xy.emplace_back(static_cast<double>(km), grown);
      if (m == set.states.back()) time_k.emplace_back(static_cast<double>(k), cpu);
      if (k == set.robots.back()) time_m.emplace_back(static_cast<double>(m), cpu);
      char name[32];
      std::snprintf(name, sizeof name, "%zu x %zu", k, m);
      if (unit_min_case.empty() || per_unit_us < unit_min) unit_min = per_unit_us, unit_min_case = name;
      if (unit_max_case.empty() || per_unit_us > unit_max) unit_max = per_unit_us, unit_max_case = name;
      if (target) {
        v.ran_target = true;
        v.target_ms = med;
        v.target_cpu_ms = cpu;
        v.target_mb = r.rss_peak_mb;
        v.time_pass = med <= kScaleTargetMs;
        v.memory_pass = r.rss_peak_mb <= kScaleTargetMb;
      }
    }
  }
  if (time_xy.size() < 2) return v;  // one case (--relay): no growth to fit
  std::printf("growth of the CPU median (least-squares slope on log-log; 1 = linear): time ~ (k*m)^%.2f over every "
              "case; at m = %zu, time ~ k^%.2f; at k = %zu, time ~ m^%.2f; verify's RSS ~ (k*m)^%.2f\n",
              growth_exponent(time_xy), set.states.back(), growth_exponent(time_k), set.robots.back(),
              growth_exponent(time_m), growth_exponent(memory_xy));
  std::printf("CPU per k*m: lowest %.1f us (%s), highest %.1f us (%s), %.1f times the lowest\n", unit_min,
              unit_min_case.c_str(), unit_max, unit_max_case.c_str(), unit_min > 0.0 ? unit_max / unit_min : 0.0);
  std::printf("RSS before = the child's peak after building the mission and models (it inherits this process's "
              "pages); peak RSS = its peak after verifying; verify's RSS = the difference\n");
  return v;
}

void print_usage() {
  std::fprintf(stderr,
               "usage: bench_verifier [--quick | --relay K M]\n"
               "  --quick      fewer runs and k up to 8 (a smoke test)\n"
               "  --relay K M  only the relay case of K robots x M states (to profile it, e.g. under perf record)\n");
}

/// Reads a positive case size for --relay; 0 if `text` is not one.
std::size_t parse_case_size(const char* text) {
  char* end = nullptr;
  const unsigned long value = std::strtoul(text, &end, 10);
  return (end != text && *end == '\0' && value > 0 && value <= 256) ? static_cast<std::size_t>(value) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::size_t relay_k = 0, relay_m = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
    } else if (std::strcmp(argv[i], "--relay") == 0 && i + 2 < argc) {
      relay_k = parse_case_size(argv[i + 1]);
      relay_m = parse_case_size(argv[i + 2]);
      if (relay_k == 0 || relay_m == 0) {
        print_usage();
        return 2;
      }
      i += 2;
    } else {
      print_usage();
      return 2;
    }
  }
  log::threshold() = log::Level::warn;

  if (relay_k != 0) {
    ScaleSettings one;
    one.robots = {relay_k};
    one.states = {relay_m};
    bench_relay_scaling(one);
    return 0;
  }
  const int runs = quick ? 5 : 20;
  const BoVerdicts bo = bench_bounding_overwatch(runs);
  if (!bo.ran) return 2;
  ScaleSettings scaling;
  scaling.robots = quick ? std::vector<std::size_t>{2, 4, 8} : std::vector<std::size_t>{2, 4, 8, 16, 32};
  scaling.states = {4, 8, 12, 16, 20};
  if (quick) {
    scaling.max_runs = 3;
    scaling.budget_ms = 300.0;
    scaling.limit_s = 60;
  }
  const ScaleVerdicts scale = bench_relay_scaling(scaling);

  std::printf("\nverifier targets (issue #4), judged on the wall-clock median (CPU median in brackets: when the "
              "machine is busy the wall clock also counts other processes' time):\n");
  std::printf("%s  Bounding Overwatch, one point: median %.2f ms (CPU %.2f ms, p90 %.2f ms) <= %.0f ms\n",
              verdict(bo.point_pass).c_str(), bo.point_ms, bo.point_cpu, bo.point_p90, kPointTargetMs);
  std::printf("%s  Bounding Overwatch, 51 x 41 grid: median %.2f ms (CPU %.2f ms, p90 %.2f ms) <= %.0f ms\n",
              verdict(bo.grid_pass).c_str(), bo.grid_ms, bo.grid_cpu, bo.grid_p90, kGridTargetMs);
  if (scale.ran_target) {
    std::printf("%s  relay %zu x %zu: median %.1f ms (CPU %.1f ms) <= %.0f ms\n", verdict(scale.time_pass).c_str(),
                kScaleTargetRobots, kScaleTargetStates, scale.target_ms, scale.target_cpu_ms, kScaleTargetMs);
    std::printf("%s  relay %zu x %zu: peak RSS %.1f MB <= %.0f MB\n", verdict(scale.memory_pass).c_str(),
                kScaleTargetRobots, kScaleTargetStates, scale.target_mb, kScaleTargetMb);
  } else if (quick) {
    std::printf("SKIP  relay %zu x %zu time and memory (--quick stops at k = 8)\n", kScaleTargetRobots,
                kScaleTargetStates);
  } else {
    std::printf("FAIL  relay %zu x %zu time <= %.0f ms: %s\n", kScaleTargetRobots, kScaleTargetStates, kScaleTargetMs,
                scale.target_error.c_str());
    std::printf("FAIL  relay %zu x %zu peak RSS <= %.0f MB: not measured (%s)\n", kScaleTargetRobots,
                kScaleTargetStates, kScaleTargetMb, scale.target_error.c_str());
  }
  return 0;
}
