// What a generated mission exercises, counted from the loaded mission and
// world: the coverage table of docs/crosscheck.md and the generator's tests.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "gen_internal.hpp"

namespace p3at::mission_gen {
namespace {

bool has_cycle(const mission::RobotSpec& r) {
  std::vector<int> mark(r.states.size(), 0);  // 0 new, 1 on the stack, 2 done
  std::function<bool(std::size_t)> visit = [&](std::size_t s) {
    mark[s] = 1;
    for (std::size_t t : r.states[s].outgoing) {
      const std::size_t to = r.transitions[t].to;
      if (mark[to] == 1 || (mark[to] == 0 && visit(to))) return true;
    }
    mark[s] = 2;
    return false;
  };
  return visit(r.initial);
}

}  // namespace

Coverage coverage(const GeneratedMission& g) {
  using mission::BehaviorKind;
  using mission::TriggerKind;
  const double inf = std::numeric_limits<double>::infinity();
  Coverage c;
  c.robots = g.mission.robots.size();
  c.min_leg_m = c.min_speed_mps = c.min_dropoff_m = c.min_random_trans = inf;
  for (const mission::RobotSpec& r : g.mission.robots) {
    c.min_speed_mps = std::min(c.min_speed_mps, r.max_speed_mps);
    c.max_speed_mps = std::max(c.max_speed_mps, r.max_speed_mps);
    Point2 at{r.start.x_m, r.start.y_m};
    for (const mission::State& s : r.states) {
      if (s.kind() == BehaviorKind::go_to_guarded) {
        const auto& p = std::get<mission::GoToGuardedParams>(s.behavior);
        const double leg = dist(at, p.goal);
        at = p.goal;
        ++c.go_to_states;
        c.min_leg_m = std::min(c.min_leg_m, leg);
        c.max_leg_m = std::max(c.max_leg_m, leg);
        c.min_dropoff_m = std::min(c.min_dropoff_m, p.dropoff_m);
        c.max_dropoff_m = std::max(c.max_dropoff_m, p.dropoff_m);
        c.max_noise_gain = std::max(c.max_noise_gain, p.noise_gain);
        if (p.noise_gain > 0 && p.noise_persistence_cycles == 1) ++c.noise_redrawn_every_cycle;
        if (p.noise_gain > 0 && static_cast<double>(p.noise_persistence_cycles) >= leg / r.max_speed_mps / 0.1) {
          ++c.noise_held_whole_leg;
        }
      }
      bool at_goal = false, notified = false;
      for (std::size_t t : s.outgoing) {
        const mission::Transition& tr = r.transitions[t];
        at_goal = at_goal || tr.kind() == TriggerKind::at_goal;
        notified = notified || tr.kind() == TriggerKind::notified;
        if (tr.kind() == TriggerKind::has_turned && s.kind() == BehaviorKind::spin) {
          ++c.spins;
          if (std::get<mission::HasTurnedParams>(tr.trigger).offset_deg > 0) ++c.spin_offsets;
        }
        if (tr.kind() == TriggerKind::notified) {
          if (s.kind() == BehaviorKind::go_to_guarded) ++c.notified_from_moving;
          if (s.kind() == BehaviorKind::spin) ++c.notified_from_spin;
          if (s.kind() == BehaviorKind::stop) ++c.notified_from_stop;
        }
      }
      if (at_goal && notified) ++c.at_goal_racing_notified;
    }
    if (has_cycle(r)) ++c.loops;
  }
  for (const mission::Message& m : g.mission.messages) c.multi_recipient_messages += m.to.size() >= 2;
  for (std::size_t i = 0; i < g.routes.size(); ++i) {
    for (std::size_t j = i + 1; j < g.routes.size(); ++j) {
      bool cross = false;
      const auto& a = g.routes[i].points;
      const auto& b = g.routes[j].points;
      for (std::size_t p = 0; p + 1 < a.size() && !cross; ++p) {
        for (std::size_t q = 0; q + 1 < b.size() && !cross; ++q) cross = segments_cross({a[p], a[p + 1]}, {b[q], b[q + 1]});
      }
      c.crossing_paths += cross;
    }
  }
  c.world = g.features;
  for (const sim::RobotConfig& r : g.world.robots) {
    const sim::OdometryErrors& e = r.odometry;
    if (std::abs(e.left_scale - 1) > 0.005 || std::abs(e.right_scale - 1) > 0.005 || std::abs(e.track_ratio - 1) > 0.005) {
      ++c.systematic_error_robots;
    }
    c.min_random_trans = std::min(c.min_random_trans, e.random_trans_per_unit);
    c.max_random_trans = std::max(c.max_random_trans, e.random_trans_per_unit);
  }
  c.lossy_radio = g.world.radio.loss_probability > 0;
  c.slow_radio = g.world.radio.slow_probability > 0;
  return c;
}

}  // namespace p3at::mission_gen
