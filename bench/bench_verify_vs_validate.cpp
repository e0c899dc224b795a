// Benchmark: the verifier against the validation it replaces (issue #5), in
// one run, on the Bounding Overwatch example and the paper's grid:
//  - verify()'s time for the 51 x 41 grid (Tmax 170..220 s step 1, Rmax
//    1..3 m step 0.05), one thread: median over repeats after a warm-up;
//  - the validation's measured throughput: N runs (default 200) as a
//    `vipars validate` campaign (team_sim::run_campaign) on one thread and on
//    every core, plus the grid's empirical probabilities over those runs;
//  - extrapolated to the runs an accuracy of eps = delta = 0.01 needs by
//    Hoeffding's inequality, n = ceil(ln(2/delta) / (2 eps^2)) = 26,492: the
//    validation's time for the same grid, and the ratio to the verifier's
//    (target: the verifier at least 100x faster);
//  - validation throughput in runs per second per core.
// Wall-clock and CPU figures side by side: on a busy machine the wall clock
// counts other processes' time too. Exit status 0 whatever the verdict (a
// benchmark reports); 2 when the example does not load or verify.
// Usage: bench_verify_vs_validate [--runs N] [--repeats K]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

using namespace p3at;

namespace {

constexpr double kTargetRatio = 100.0;
constexpr double kEpsilon = 0.01, kDelta = 0.01;

double cpu_s(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) / 1e9;
}

struct Elapsed {
  double wall_s = 0.0, cpu_s = 0.0;
};

/// Wall time and CPU time of `f`: the calling thread's (one-thread work) or
/// the whole process's (a campaign's workers).
template <class F>
Elapsed timed(clockid_t clock, F&& f) {
  const double c0 = cpu_s(clock);
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), cpu_s(clock) - c0};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<double> axis(double a, double step, std::size_t count) {
  std::vector<double> v;
  for (std::size_t i = 0; i < count; ++i) v.push_back(std::round((a + step * static_cast<double>(i)) * 1e9) / 1e9);
  return v;
}

/// Runs Hoeffding's inequality asks for: P(|p̂ − p| ≥ eps) ≤ 2 exp(−2 n eps²) ≤ delta.
std::uint64_t hoeffding_runs(double eps, double delta) {
  return static_cast<std::uint64_t>(std::ceil(std::log(2.0 / delta) / (2.0 * eps * eps)));
}

std::string duration(double s) {
  char buf[48];
  if (s < 1.0) {
    std::snprintf(buf, sizeof buf, "%.1f ms", s * 1e3);
  } else if (s < 120.0) {
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f min", s / 60.0);
  }
  return buf;
}

void row(const char* what, const std::string& value) { std::printf("| %-62s | %20s |\n", what, value.c_str()); }

std::string number(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t runs = 200;
  int repeats = 10;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_verify_vs_validate [--runs N] [--repeats K]\n");
      return 2;
    }
  }
  if (runs < 1 || repeats < 1) {
    std::fprintf(stderr, "bench_verify_vs_validate: --runs and --repeats must be at least 1\n");
    return 2;
  }
  const std::string dir = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/";
  try {
    const mission::Mission mission = mission::load_mission_file(dir + "mission.yaml");
    const verifier::Models models = verifier::load_models_file(dir + "models.yaml");
    const team_sim::TeamScenario scenario(mission, sim::load_world_file(dir + "world.yaml"));

    // 1. The verifier on the grid, one thread.
    verifier::VerifyOptions options;
    options.tmax_grid = axis(170.0, 1.0, 51);
    options.rmax_grid = axis(1.0, 0.05, 41);
    const std::size_t cells = options.tmax_grid.size() * options.rmax_grid.size();
    double p_success = 0.0;
    std::vector<double> verify_wall, verify_cpu;
    for (int i = 0; i <= repeats; ++i) {  // i == 0: warm-up, not counted
      bool ok = true;
      const Elapsed e = timed(CLOCK_THREAD_CPUTIME_ID, [&] {
        auto r = verifier::verify(mission, models, options);
        ok = r.ok();
        if (ok) p_success = r->p_joint;
      });
      if (!ok) {
        std::fprintf(stderr, "bench_verify_vs_validate: the example does not verify\n");
        return 2;
      }
      if (i > 0) {
        verify_wall.push_back(e.wall_s);
        verify_cpu.push_back(e.cpu_s);
      }
    }
    const double v_wall = median(verify_wall), v_cpu = median(verify_cpu);

    // 2. The validation's throughput: the same campaign on one thread, then on every core.
    team_sim::CampaignOptions one;
    one.runs = runs;
    one.jobs = 1;
    std::vector<team_sim::RunResult> results;
    const Elapsed c1 = timed(CLOCK_PROCESS_CPUTIME_ID, [&] { results = team_sim::run_campaign(scenario, one); });
    team_sim::CampaignOptions all;
    all.runs = runs;
    all.seed = 2;  // other runs than the first campaign's, same mission
    const unsigned jobs = team_sim::campaign_jobs(all);
    const Elapsed cn = timed(CLOCK_PROCESS_CPUTIME_ID, [&] { (void)team_sim::run_campaign(scenario, all); });
    const Elapsed grid = timed(CLOCK_THREAD_CPUTIME_ID,
                               [&] { (void)team_sim::empirical_grid(results, options.tmax_grid, options.rmax_grid); });
    std::uint64_t succeeded = 0;
    for (const auto& r : results) {
      if (r.success()) ++succeeded;
    }

    // 3. Extrapolated to Hoeffding's runs, linearly (the grid's cost grows with the runs too).
    const std::uint64_t n = hoeffding_runs(kEpsilon, kDelta);
    const double scale = static_cast<double>(n) / static_cast<double>(runs);
    const double rps_1 = static_cast<double>(runs) / c1.wall_s;
    const double rps_n = static_cast<double>(runs) / cn.wall_s;
    const double rps_cpu = static_cast<double>(runs) / c1.cpu_s;  // runs per CPU-second
    const double t_1 = c1.wall_s * scale + grid.wall_s * scale;
    const double t_n = cn.wall_s * scale + grid.wall_s * scale;
    const double t_cpu = c1.cpu_s * scale + grid.cpu_s * scale;

    std::printf(
        "\nverification vs. validation: %s, grid %zu x %zu = %zu cells; validation measured on %llu runs, "
        "extrapolated to %llu (Hoeffding, eps = delta = %.2f)\n",
        mission.name.c_str(), options.tmax_grid.size(), options.rmax_grid.size(), cells,
        static_cast<unsigned long long>(runs), static_cast<unsigned long long>(n), kEpsilon);
    std::printf("| %-62s | %20s |\n|%s|%s|\n", "measure", "value", std::string(64, '-').c_str(),
                std::string(22, '-').c_str());
    row("verify(), full grid, 1 thread: median wall", duration(v_wall));
    row("verify(), full grid, 1 thread: median CPU", duration(v_cpu));
    row(("validation runs/s, 1 thread (" + std::to_string(runs) + " runs)").c_str(), number(rps_1, 1));
    row(("validation runs/s, " + std::to_string(jobs) + " threads").c_str(), number(rps_n, 1));
    row("validation runs/s per core (all cores)", number(rps_n / jobs, 1));
    row("validation runs per CPU-second (1 thread)", number(rps_cpu, 1));
    row(("grid's empirical probabilities over " + std::to_string(runs) + " runs").c_str(), duration(grid.wall_s));
    row(("validation, " + std::to_string(n) + " runs, 1 thread (extrapolated)").c_str(), duration(t_1));
    row(("validation, " + std::to_string(n) + " runs, " + std::to_string(jobs) + " threads (extrapolated)").c_str(),
        duration(t_n));
    row(("validation, " + std::to_string(n) + " runs, CPU time (extrapolated)").c_str(), duration(t_cpu));
    row("ratio validation / verification, 1 thread each (wall)", number(t_1 / v_wall, 0) + "x");
    row(("ratio validation on " + std::to_string(jobs) + " threads / verification on 1 (wall)").c_str(),
        number(t_n / v_wall, 0) + "x");
    row("ratio validation / verification (CPU time)", number(t_cpu / v_cpu, 0) + "x");
    std::printf("\nverified P(success) at the mission's criterion %.4f; %llu of %llu measured runs succeeded\n",
                p_success, static_cast<unsigned long long>(succeeded), static_cast<unsigned long long>(runs));
    // Judged on the validation with every core against the verifier on one: the least favourable to the verifier.
    const double ratio = t_n / v_wall;
    std::printf("%s: verifier at least %.0fx faster than the validation on every core (%.0fx)\n",
                ratio >= kTargetRatio ? "PASS" : "FAIL", kTargetRatio, ratio);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_verify_vs_validate: %s\n", e.what());
    return 2;
  }
}
