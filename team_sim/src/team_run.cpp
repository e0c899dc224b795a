#include "p3at/team_sim/team_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <variant>
#include <limits>
#include <memory>
#include <stdexcept>

#include "p3at/common/log.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/team_link/team_key.hpp"
#include "p3at/sim/radio.hpp"
#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/world.hpp"

namespace p3at::team_sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A heading in degrees within (-180, 180], for the run's report.
double wrapped_deg(double theta_rad) { return std::remainder(theta_rad, 2.0 * kPi) * 180.0 / kPi; }

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

/// Distance from (x, y) to the nearest wall of the world (infinity without walls).
double nearest_wall_m(const sim::WorldConfig& world, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : world.walls) {
    const double dx = w.b.x - w.a.x, dy = w.b.y - w.a.y;
    const double len2 = dx * dx + dy * dy;
    const double t = len2 > 0.0 ? std::clamp(((x - w.a.x) * dx + (y - w.a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - (w.a.x + t * dx), y - (w.a.y + t * dy)));
  }
  return best;
}

/// Why a robot still running at the timeout has not finished, without
/// --verbose: waiting for a message (which, from whom), or not moving (where,
/// how close to a wall: pinned), or still on its way.
/// `brief` is the same without numbers, so that runs stuck alike group
/// together in vipars validate's failure list.
std::string why_not_finished(const mission::Mission& mission, std::size_t i, const std::string& state_name, double x,
                             double y, double still_s, double wall_m, std::string& brief) {
  const mission::RobotSpec& spec = mission.robots[i];
  const auto state = spec.find_state(state_name);
  std::string where = "in state '" + state_name + "' at (" + format_fixed(x, 2) + ", " + format_fixed(y, 2) + ")";
  brief = spec.name + " in '" + state_name + "'";
  if (!state) return where;
  std::string waits;
  bool only_messages = !spec.states[*state].outgoing.empty();
  for (const std::size_t t : spec.states[*state].outgoing) {
    const auto* n = std::get_if<mission::NotifiedParams>(&spec.transitions[t].trigger);
    if (n == nullptr) {
      only_messages = false;
      continue;
    }
    std::string from;
    if (const auto m = mission.find_message(n->message)) from = " from " + mission.robots[mission.messages[*m].from].name;
    waits += (waits.empty() ? "" : " or ") + ("'" + n->message + "'" + from);
  }
  const bool moving = spec.states[*state].kind() == mission::BehaviorKind::go_to_guarded ||
                      spec.states[*state].kind() == mission::BehaviorKind::spin;
  if (only_messages && !moving) {
    brief += " waiting for " + waits;
    return where + ", waiting for " + waits + ", never received";
  }
  if (moving && still_s >= 10.0) {
    brief += " not moving (pinned)";
    return where + ", has not moved for " + format_fixed(still_s, 0) + " s, " + format_fixed(wall_m, 2) +
           " m from the nearest wall (pinned" + (waits.empty() ? "" : "; or waiting for " + waits) + ")";
  }
  brief += " still moving";
  return where + (waits.empty() ? ", still on its way" : ", still on its way (or waiting for " + waits + ")");
}

/// True when no robot of the world moves: both velocities of every base are
/// zero (the simulated firmware's ramps brake to exactly zero, so the bound
/// only guards against rounding).
bool all_at_rest(const sim::World& world) {
  constexpr double kRestMps = 1e-9, kRestRadps = 1e-9;
  for (std::size_t i = 0; i < world.robot_count(); ++i) {
    const sim::MotionController& c = world.robot(i).controller();
    if (std::abs(c.trans_vel_mps()) > kRestMps || std::abs(c.rot_vel_radps()) > kRestRadps) return false;
  }
  return true;
}

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
  const auto rest_us = static_cast<std::int64_t>(options.rest_s * 1e6);
  std::int64_t all_ended_us = -1;
  // Where each robot last moved (10 cm or more), and when: for a timeout's reason.
  std::vector<std::pair<double, double>> last_moved_xy(n);
  std::vector<std::int64_t> last_moved_us(n, 0);
  for (std::size_t i = 0; i < n; ++i) last_moved_xy[i] = {world.robot(i).true_pose().x_m, world.robot(i).true_pose().y_m};
  while (world.time_us() < timeout_us) {
    for (auto& d : drives) (void)d->wait_for_update(150);  // the first steps the world
    for (auto& e : executives) e->cycle();
    ++result.cycles;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = world.robot(i).true_pose();
      if (std::hypot(p.x_m - last_moved_xy[i].first, p.y_m - last_moved_xy[i].second) >= 0.1) {
        last_moved_xy[i] = {p.x_m, p.y_m};
        last_moved_us[i] = world.time_us();
      }
    }
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
      // A finished mission's final positions are where the robots come to
      // rest: each executive stopped its base on entering its final state,
      // and the base brakes from the speed it had (a robot that finished
      // early has long stopped; the last one is still braking now). An abort
      // is recorded where it stands.
      const bool all_finished = std::all_of(executives.begin(), executives.end(), [](const auto& e) {
        return e->outcome().phase == exec::Phase::finished;
      });
      const bool resting = !all_finished || all_at_rest(world) || world.time_us() - all_ended_us >= rest_us;
      if ((settled || world.time_us() - all_ended_us >= settle_us) && resting) break;
    }
  }
  if (n < 2) result.closest_approach_m = 0.0;

  std::string first_abort;
  std::string timed_out;  // every robot still running: who, in which state, where, why
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
    r.true_theta_deg = wrapped_deg(robot.true_pose().theta_rad);
    r.odom_theta_deg = wrapped_deg(believed.theta_rad);
    r.dist_to_goal_m = std::hypot(r.true_x_m - goals_[i].x_m, r.true_y_m - goals_[i].y_m);
    r.cycle_p50_us = e.stats().p50_us();
    r.cycle_p99_us = e.stats().p99_us();
    if (e.outcome().phase != exec::Phase::finished) all_finished = false;
    if (e.outcome().phase == exec::Phase::running) {
      std::string brief;
      r.reason = why_not_finished(mission_, i, e.state_name(), r.true_x_m, r.true_y_m,
                                  static_cast<double>(world.time_us() - last_moved_us[i]) / 1e6,
                                  nearest_wall_m(world_, r.true_x_m, r.true_y_m), brief);
      timed_out += (timed_out.empty() ? "" : "; ") + brief;
    }
    if (e.outcome().phase == exec::Phase::aborted && first_abort.empty()) first_abort = r.name + ": " + r.reason;
    result.time_s = std::max(result.time_s, r.end_time_s);
    result.robots.push_back(std::move(r));
  }
  if (all_finished) {
    result.outcome = "success";
  } else if (!first_abort.empty()) {
    result.outcome = "aborted (" + first_abort + ")";
  } else {
    result.outcome = "timeout (" + timed_out + ")";
    result.time_s = options.timeout_s;
  }
  return result;
}

}  // namespace p3at::team_sim
