#pragma once
// One robot driving one GoToGuarded leg along x from the origin (AtGoal radius
// 0.2 m, dead zone 0.05 m unless given), then stopping: the smallest mission a NOISE test
// needs (test_noise_redraw.cpp, test_noise_directions.cpp).

#include <string>

#include "p3at/mission/loader.hpp"

namespace p3at::verifier::test {

inline mission::Mission one_leg_mission(double length_m, double dropoff_m, double gain, long persistence,
                                        double at_goal_radius_m = 0.2, double dead_zone_m = 0.05) {
  const std::string text = "mission: {name: leg}\n"
                           "criteria: {tmax_s: 100, rmax_m: 1.0, threshold: 0.5}\n"
                           "robots:\n"
                           "  - name: r\n"
                           "    start: {x_m: 0.0, y_m: 0.0, theta_deg: 0}\n"
                           "    hal: tcp://127.0.0.1:8101\n"
                           "    states:\n"
                           "      - {name: go, behavior: GoToGuarded, params: {goal: [" +
                           std::to_string(length_m) + ", 0.0], dropoff_m: " + std::to_string(dropoff_m) +
                           ", dead_zone_m: " + std::to_string(dead_zone_m) + ", noise_gain: " + std::to_string(gain) +
                           ", noise_persistence_cycles: " + std::to_string(persistence) +
                           "}}\n"
                           "      - {name: done, behavior: Stop}\n"
                           "    transitions:\n"
                           "      - {from: go, to: done, trigger: AtGoal, params: {radius_m: " + std::to_string(at_goal_radius_m) +
                           "}}\n";
  return mission::parse_mission(text, "leg.yaml");
}

}  // namespace p3at::verifier::test
