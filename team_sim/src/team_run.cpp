#include "p3at/team_sim/team_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "p3at/common/log.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/team_link/team_key.hpp"
#include "p3at/sim/radio.hpp"
#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/world.hpp"

namespace p3at::team_sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The simulated radio authenticates like the real link; the key's value is
// irrelevant inside one process, so a fixed one keeps runs identical.
hal::TeamKey simulation_key() {
  hal::TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(0x5A ^ (i * 7));
  return hal::TeamKey(bytes);
}

// Silences the executives' per-transition log lines for the run's duration.
class LogThresholdGuard {
 public:
  // Writes the global threshold only when it has to change it, so runs on
  // several threads (whose campaign lowered it once up front) never write it.
  explicit LogThresholdGuard(bool verbose)
      : saved_(log::threshold()), changed_(!verbose && saved_ < log::Level::warn) {
    if (changed_) log::threshold() = log::Level::warn;
  }
  ~LogThresholdGuard() {
    if (changed_) log::threshold() = saved_;
  }
  LogThresholdGuard(const LogThresholdGuard&) = delete;
  LogThresholdGuard& operator=(const LogThresholdGuard&) = delete;

 private:
  log::Level saved_;
  bool changed_;
};

}  // namespace

TeamScenario::TeamScenario(mission::Mission mission, const sim::WorldConfig& world) : mission_(std::move(mission)) {
  world_ = world;
  world_.robots.clear();
  // The world file gives each robot's error model; the mission says where it starts.
  for (const auto& spec : mission_.robots) {
    const auto it = std::find_if(world.robots.begin(), world.robots.end(),
                                 [&](const sim::RobotConfig& r) { return r.name == spec.name; });
    if (it == world.robots.end()) {
      throw std::invalid_argument("the world has no robot named '" + spec.name +
                                  "' (every mission robot needs an entry with its error model)");
    }
    sim::RobotConfig robot = *it;
    robot.start = {spec.start.x_m, spec.start.y_m, spec.start.theta_deg * kPi / 180.0};
    world_.robots.push_back(robot);
    goals_.push_back(spec.goal);  // resolved by the mission loader
  }
}

RunResult TeamScenario::run(std::uint64_t run_index, std::uint64_t seed, const RunOptions& options) const {
  const LogThresholdGuard quiet(options.log_transitions);
  sim::World world(world_, seed);
  auto radio = sim::SimRadio::create(world_.radio, seed);
  if (!radio) throw std::invalid_argument(radio.error().message);

  const std::size_t n = mission_.robots.size();
  std::vector<std::string> roster;
  for (const auto& r : mission_.robots) roster.push_back(r.name);
  const hal::TeamKey key = simulation_key();

  std::vector<std::unique_ptr<sim::SimDriveBase>> drives;
  std::vector<std::unique_ptr<sim::SimTeamLink>> links;
  std::vector<std::unique_ptr<exec::RobotExecutive>> executives;
  for (std::size_t i = 0; i < n; ++i) {
    drives.push_back(std::make_unique<sim::SimDriveBase>(world, i));
    hal::TeamLinkConfig config;
    config.mission_id = mission_.name;
    config.self = mission_.robots[i].name;
    config.roster = roster;
    auto link = sim::SimTeamLink::create(*radio.value(), config, key);
    if (!link) throw std::invalid_argument(link.error().message);
    links.push_back(std::move(link).value());
    exec::ExecutiveOptions exec_options;
    exec_options.seed = seed;
    exec_options.telemetry_every_cycles = 0;  // nobody listens in fast time
    exec_options.status_every_cycles = 0;
    executives.push_back(
        std::make_unique<exec::RobotExecutive>(mission_, i, *drives[i], *links[i], world.clock(), exec_options));
  }

  RunResult result;
  result.run = run_index;
  result.seed = seed;
  result.closest_approach_m = std::numeric_limits<double>::infinity();
  const auto timeout_us = static_cast<std::int64_t>(options.timeout_s * 1e6);
  const auto settle_us = static_cast<std::int64_t>(options.settle_s * 1e6);
  std::int64_t all_ended_us = -1;
  while (world.time_us() < timeout_us) {
    for (auto& d : drives) (void)d->wait_for_update(150);  // the first steps the world
    for (auto& e : executives) e->cycle();
    ++result.cycles;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        const auto& a = world.robot(i).true_pose();
        const auto& b = world.robot(j).true_pose();
        result.closest_approach_m = std::min(result.closest_approach_m, std::hypot(a.x_m - b.x_m, a.y_m - b.y_m));
      }
    }
    const bool any_running = std::any_of(executives.begin(), executives.end(), [](const auto& e) { return e->running(); });
    if (!any_running) {
      if (all_ended_us < 0) all_ended_us = world.time_us();
      // Give teammates' last acknowledgements a moment, as mission_exec does.
      const bool settled = std::all_of(executives.begin(), executives.end(), [](const auto& e) { return e->team_settled(); });
      if (settled || world.time_us() - all_ended_us >= settle_us) break;
    }
  }
  if (n < 2) result.closest_approach_m = 0.0;

  std::string first_abort;
  bool all_finished = true;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& e = *executives[i];
    const auto& robot = world.robot(i);
    RobotResult r;
    r.name = mission_.robots[i].name;
    r.phase = exec::to_string(e.outcome().phase);
    r.reason = e.outcome().reason;
    r.end_time_s = e.elapsed_s();
    r.true_x_m = robot.true_pose().x_m;
    r.true_y_m = robot.true_pose().y_m;
    const auto believed = robot.odometry_in_world();
    r.odom_x_m = believed.x_m;
    r.odom_y_m = believed.y_m;
    r.dist_to_goal_m = std::hypot(r.true_x_m - goals_[i].x_m, r.true_y_m - goals_[i].y_m);
    r.cycle_p50_us = e.stats().p50_us();
    r.cycle_p99_us = e.stats().p99_us();
    if (e.outcome().phase != exec::Phase::finished) all_finished = false;
    if (e.outcome().phase == exec::Phase::aborted && first_abort.empty()) first_abort = r.name + ": " + r.reason;
    result.time_s = std::max(result.time_s, r.end_time_s);
    result.robots.push_back(std::move(r));
  }
  if (all_finished) {
    result.outcome = "success";
  } else if (!first_abort.empty()) {
    result.outcome = "aborted (" + first_abort + ")";
  } else {
    result.outcome = "timeout";
    result.time_s = options.timeout_s;
  }
  return result;
}

}  // namespace p3at::team_sim
