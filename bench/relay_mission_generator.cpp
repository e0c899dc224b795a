#include "relay_mission_generator.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "p3at/mission/loader.hpp"

namespace p3at::bench {
namespace {

constexpr double kStartX = 2.0;       // metres from the rectangle's west wall
constexpr double kLaneY0 = 2.0;       // robot 0's lane; 2 m from the south wall
constexpr double kLaneSpacing = 2.0;  // > 1.15 m: obstacles repel within radius 0.4 + margin 0.25 + sphere 0.5
constexpr double kBoundM = 2.5;       // one bound along the lane
constexpr double kWallMarginM = 2.0;  // from the outermost start/goal to the walls
constexpr double kSecondsPerBound = 12.0;  // 2.5 m at 0.3 m/s with ramps, plus the token's delay, rounded up

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

std::string robot_name(std::size_t i) { return "robot" + std::to_string(i); }
// The token robot i passes to robot i + 1 (mod k) on trip `trip`.
std::string token(std::size_t from, std::size_t trip) {
  return "tok_" + std::to_string(from) + "_" + std::to_string(trip);
}
std::string lane_y(std::size_t i) { return number(kLaneY0 + kLaneSpacing * static_cast<double>(i)); }
std::string bound_x(std::size_t trip) { return number(kStartX + kBoundM * static_cast<double>(trip)); }

// The same guards as the Bounding Overwatch example: full speed until 0.5 m
// out, AtGoal at 0.3 m, one wander direction per bound.
std::string bound_state(std::size_t robot, std::size_t trip) {
  return "      - {name: bound_" + std::to_string(trip) + ", behavior: GoToGuarded, params: {goal: [" + bound_x(trip) +
         ", " + lane_y(robot) +
         "], dropoff_m: 0.5, dead_zone_m: 0.05, sphere_m: 0.5, safety_margin_m: 0.25, noise_gain: 0.135, "
         "noise_persistence_cycles: 600}}\n";
}
std::string simple_state(const std::string& name, const std::string& behavior, const std::string& params = {}) {
  return "      - {name: " + name + ", behavior: " + behavior + (params.empty() ? "" : ", params: " + params) + "}\n";
}
std::string transition(const std::string& from, const std::string& to, const std::string& trigger,
                       const std::string& params = {}) {
  return "      - {from: " + from + ", to: " + to + ", trigger: " + trigger +
         (params.empty() ? "" : ", params: " + params) + "}\n";
}

std::string robot_yaml(std::size_t i, std::size_t robots, std::size_t trips) {
  const std::size_t previous_index = (i + robots - 1) % robots;
  std::string states, transitions;
  for (std::size_t t = 1; t <= trips; ++t) {
    const std::string n = std::to_string(t);
    const bool last = t == trips;
    const std::string wait = "wait_" + n, bound = "bound_" + n, tell = "tell_" + n;
    const std::string after_tell = last ? (i == 0 ? wait : std::string("done")) : "scan_" + n;
    const std::string notified = "{message: " + token(previous_index, t) + "}";
    if (i != 0) {
      states += simple_state(wait, "Stop");
      transitions += transition(wait, bound, "Notified", notified);
    }
    states += bound_state(i, t);
    transitions += transition(bound, tell, "AtGoal", "{radius_m: 0.3}");
    states += simple_state(tell, "Notify", "{message: " + token(i, t) + "}");
    transitions += transition(tell, after_tell, "MessageSent");
    if (!last) {
      states += simple_state("scan_" + n, "Spin", "{rate_deg_s: 60}");
      // Robot 0 waits for the token after its scan; the others wait at the start of the next trip.
      const std::string after_scan = i == 0 ? wait : "wait_" + std::to_string(t + 1);
      transitions += transition("scan_" + n, after_scan, "HasTurned", "{angle_deg: 360}");
    }
    if (i == 0) {
      states += simple_state(wait, "Stop");
      transitions += transition(wait, last ? std::string("done") : "bound_" + std::to_string(t + 1), "Notified", notified);
    }
  }
  states += simple_state("done", "Stop");
  return "  - name: " + robot_name(i) + "\n    start: {x_m: " + number(kStartX) + ", y_m: " + lane_y(i) +
         ", theta_deg: 0}\n    hal: tcp://127.0.0.1:" + std::to_string(8101 + i) +
         "\n    max_speed_mps: 0.3\n    initial: " + (i == 0 ? "bound_1" : "wait_1") + "\n    states:\n" + states +
         "    transitions:\n" + transitions;
}

}  // namespace

std::string relay_mission_yaml(std::size_t robots, std::size_t states_per_robot) {
  if (robots < 2) throw std::invalid_argument("relay mission: need at least 2 robots");
  if (states_per_robot == 0 || states_per_robot % 4 != 0) {
    throw std::invalid_argument("relay mission: states per robot must be a positive multiple of 4, got " +
                                std::to_string(states_per_robot));
  }
  const std::size_t trips = states_per_robot / 4;
  // Tmax: half as long again as the expected completion (every bound in turn),
  // plus a minute. Rmax 1.5 m: the rotation scale error moves the worst robots
  // about 0.8 m off their goal over five trips, and success needs every robot in.
  const double tmax = 1.5 * kSecondsPerBound * static_cast<double>(robots * trips) + 60.0;
  std::string yaml = "mission:\n  name: relay_" + std::to_string(robots) + "x" + std::to_string(states_per_robot) +
                     "\n  description: \"generated relay: " + std::to_string(robots) + " robots, " +
                     std::to_string(states_per_robot) + " states each\"\n\ncriteria:\n  tmax_s: " + number(tmax) +
                     "\n  rmax_m: 1.5\n  threshold: 0.8\n\nrobots:\n";
  for (std::size_t i = 0; i < robots; ++i) yaml += robot_yaml(i, robots, trips);
  yaml += "\nmessages:\n";
  for (std::size_t i = 0; i < robots; ++i) {
    for (std::size_t t = 1; t <= trips; ++t) {
      yaml += "  - {name: " + token(i, t) + ", from: " + robot_name(i) + ", to: [" + robot_name((i + 1) % robots) +
              "]}\n";
    }
  }
  return yaml;
}

mission::Mission relay_mission(std::size_t robots, std::size_t states_per_robot) {
  return mission::parse_mission(relay_mission_yaml(robots, states_per_robot),
                                "relay_" + std::to_string(robots) + "x" + std::to_string(states_per_robot) + ".yaml");
}

verifier::Models relay_models(const mission::Mission& relay) {
  verifier::Models models;
  models.source = "generated relay models";
  models.generated_by = "bench/relay_mission_generator.cpp";
  double x0 = relay.robots.front().start.x_m, x1 = x0;
  double y0 = relay.robots.front().start.y_m, y1 = y0;
  for (std::size_t i = 0; i < relay.robots.size(); ++i) {
    const mission::RobotSpec& r = relay.robots[i];
    for (const double x : {r.start.x_m, r.goal.x_m}) x0 = std::min(x0, x), x1 = std::max(x1, x);
    for (const double y : {r.start.y_m, r.goal.y_m}) y0 = std::min(y0, y), y1 = std::max(y1, y);
    verifier::RobotModel model;
    model.name = r.name;
    // Systematic error varying over the robots: distance scales 0.98..1.02,
    // rotation scales 0.996..1.004 (every scan is a full turn, so a rotation
    // scale error of s turns the heading by 360° x s per trip, which the
    // odometry never sees: 0.4 % is 1.4° a trip). Random error: the Bounding
    // Overwatch example's (0.0035 m/sqrt(m), 0.0074 rad/sqrt(rad)).
    const double skew = static_cast<double>(i % 5) - 2.0;  // -2..2
    model.motion.trans_scale = 1.0 + 0.01 * skew;
    model.motion.rot_scale = 1.0 - 0.002 * skew;
    model.motion.trans_var_per_m = 0.0035 * 0.0035;
    model.motion.rot_var_per_rad = 0.0074 * 0.0074;
    models.robots.push_back(model);
  }
  // Seconds: delivery 7 ms (sd 3 ms), acknowledgement 13 ms (sd 5 ms).
  models.comm.delivery_s = verifier::Mixture1::gaussian(0.007, 0.003 * 0.003);
  models.comm.ack_s = verifier::Mixture1::gaussian(0.013, 0.005 * 0.005);
  x0 -= kWallMarginM, x1 += kWallMarginM, y0 -= kWallMarginM, y1 += kWallMarginM;
  models.environment.walls = {{x0, y0, x1, y0}, {x1, y0, x1, y1}, {x1, y1, x0, y1}, {x0, y1, x0, y0}};
  return models;
}

}  // namespace p3at::bench
