#pragma once
// Builds mission models in code, for executive tests that must not depend on
// the YAML loader: states and transitions by name, `outgoing` kept in order.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "p3at/mission/mission.hpp"

namespace p3at::test {

class RobotBuilder {
 public:
  RobotBuilder(std::string name, mission::Pose2 start) {
    spec_.name = std::move(name);
    spec_.start = start;
  }
  RobotBuilder& state(const std::string& name, mission::BehaviorParams behavior) {
    spec_.states.push_back(mission::State{name, std::move(behavior), {}});
    return *this;
  }
  RobotBuilder& transition(const std::string& from, const std::string& to, mission::TriggerParams trigger) {
    const std::size_t f = index(from);
    spec_.transitions.push_back(mission::Transition{f, index(to), std::move(trigger)});
    spec_.states[f].outgoing.push_back(spec_.transitions.size() - 1);
    return *this;
  }
  RobotBuilder& initial(const std::string& name) {
    spec_.initial = index(name);
    return *this;
  }
  RobotBuilder& max_speed(double mps) {
    spec_.max_speed_mps = mps;
    return *this;
  }
  mission::RobotSpec build() const { return spec_; }

 private:
  std::size_t index(const std::string& name) const {
    for (std::size_t i = 0; i < spec_.states.size(); ++i) {
      if (spec_.states[i].name == name) return i;
    }
    throw std::logic_error("test mission: no state " + name);
  }
  mission::RobotSpec spec_;
};

/// A mission from robots and messages given as (name, sender index, recipient indices).
inline mission::Mission make_mission(std::vector<mission::RobotSpec> robots,
                                     std::vector<mission::Message> messages = {}) {
  mission::Mission m;
  m.name = "test";
  m.criteria = mission::Criteria{60.0, 0.5, 0.8, 0.0, mission::AbortAction::continue_and_warn};
  m.robots = std::move(robots);
  m.messages = std::move(messages);
  return m;
}

/// GoToGuarded towards (x, y) without noise, for deterministic driving tests.
inline mission::GoToGuardedParams go_to(double x_m, double y_m, double noise_gain = 0.0) {
  mission::GoToGuardedParams p;
  p.goal = mission::Point2{x_m, y_m};
  p.dropoff_m = 0.5;
  p.noise_gain = noise_gain;
  return p;
}

inline mission::AtGoalParams at_goal(double x_m, double y_m, double radius_m) {
  return mission::AtGoalParams{mission::Point2{x_m, y_m}, radius_m};
}

}  // namespace p3at::test
