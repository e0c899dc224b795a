#pragma once
// Robot models for a cross-checked mission, from its world alone: each robot
// driven through the calibration manoeuvres on open floor (the world's walls
// left out, as `vipars calibrate --world` does) at its own mission speed and
// spin rate, and notifications timed over the world's radio. The mission's
// own runs are never used.

#include <cstddef>
#include <cstdint>
#include <string>

#include "p3at/protocols/mission/mission.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::crosscheck {

struct CalibratedModels {
  std::string models_yaml;   ///< the models file, walls_from: world.yaml
  std::string fit_report;    ///< the calibration's fit report (for people)
  std::string note;          ///< one line: at which speeds and rates each robot was calibrated
};

/// Throws std::runtime_error (the rig's or the fit's message) when the runs fail.
CalibratedModels calibrate_from_world(const mission::Mission& mission, const sim::WorldConfig& world,
                                      std::size_t runs, std::size_t messages, std::uint64_t seed);

}  // namespace p3at::crosscheck
