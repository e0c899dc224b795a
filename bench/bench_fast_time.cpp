// Benchmark of the executive in fast time (issue: the mission executive).
//  - whole runs per second of a mission on one core (target for the Bounding
//    Overwatch example: at least 100), per wall second and per CPU second of
//    this process (the CPU figure is the one to compare on a busy machine:
//    time the scheduler gives to other processes does not count in it)
//  - the executive's compute time per cycle, p50 and p99, measured with a real
//    steady clock inside each robot's cycle() while the world runs in fast time.
//  - validation throughput: the same runs as a `vipars validate` campaign on
//    every core (team_sim::run_campaign).
// Usage: bench_fast_time [MISSION WORLD [RUNS]]  (default: the Bounding Overwatch example, 300 runs)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/team_run.hpp"

using namespace p3at;

int main(int argc, char** argv) {
  std::string mission_file = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/mission.yaml";
  std::string world_file = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/world.yaml";
  std::uint64_t runs = 300;
  if (argc >= 3) {
    mission_file = argv[1];
    world_file = argv[2];
  }
  if (argc >= 4) runs = std::strtoull(argv[3], nullptr, 10);
  try {
    const team_sim::TeamScenario scenario(mission::load_mission_file(mission_file), sim::load_world_file(world_file));
    std::vector<double> p50, p99, sim_seconds;
    std::uint64_t successes = 0, cycles = 0;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();  // this process's CPU time; only this thread runs now
    for (std::uint64_t i = 0; i < runs; ++i) {
      const auto r = scenario.run(i, 1 + i);
      if (r.success()) ++successes;
      cycles += r.cycles;
      sim_seconds.push_back(r.time_s);
      for (const auto& robot : r.robots) {
        p50.push_back(robot.cycle_p50_us);
        p99.push_back(robot.cycle_p99_us);
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    team_sim::CampaignOptions campaign;
    campaign.runs = runs;
    const auto c0 = std::chrono::steady_clock::now();
    (void)team_sim::run_campaign(scenario, campaign);
    const double campaign_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
    std::sort(p50.begin(), p50.end());
    std::sort(p99.begin(), p99.end());
    double sim_total = 0;
    for (double s : sim_seconds) sim_total += s;
    std::printf("\nfast-time benchmark: %s, %llu runs on one core\n", scenario.mission().name.c_str(),
                static_cast<unsigned long long>(runs));
    std::printf("| measure                                      | value          |\n");
    std::printf("|----------------------------------------------|----------------|\n");
    std::printf("| whole runs per second (target >= 100)        | %14.1f |\n", static_cast<double>(runs) / wall);
    std::printf("| whole runs per CPU second (target >= 100)    | %14.1f |\n", static_cast<double>(runs) / cpu);
    std::printf("| simulated seconds per wall second            | %14.0f |\n", sim_total / wall);
    std::printf("| team cycles per second                       | %14.0f |\n", static_cast<double>(cycles) / wall);
    std::printf("| validation runs per second, %2u threads       | %14.1f |\n", team_sim::campaign_jobs(campaign),
                static_cast<double>(runs) / campaign_wall);
    std::printf("| successful runs                              | %8llu/%-5llu |\n",
                static_cast<unsigned long long>(successes), static_cast<unsigned long long>(runs));
    std::printf("| executive compute per cycle, p50 (median)    | %11.2f us |\n", p50[p50.size() / 2]);
    std::printf("| executive compute per cycle, p99 (median)    | %11.2f us |\n", p99[p99.size() / 2]);
    std::printf("| executive compute per cycle, p99 (worst run) | %11.2f us |\n", p99.back());
    std::printf("| real-time budget per cycle                   | %11.0f us |\n", 100000.0);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_fast_time: %s\n", e.what());
    return 2;
  }
}
