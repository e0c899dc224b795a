#pragma once
// The calibration manoeuvres, driven through the normal HAL (any
// hal::DriveBase: a simulated robot in fast time, p3at_sim or a real Pioneer
// over ARCOS), recording what a lab can record: each cycle's command and
// odometry, and the true pose from whatever measures it.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "p3at/hal/drive_base.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::vipars {

/// What each run drives, in order (docs/calibration.md):
///   a straight at speed_mps, a spin of +spin_deg at spin_rate_degps,
///   a straight at speed_mps / 2, a spin of -spin_deg at spin_rate_degps / 2,
///   a spin of +spin_deg and one of -spin_deg commanded at fast_spin_degps
/// (faster than any P3-AT turns: they measure the rotational cap). The two
/// speeds tell the per-unit from the per-cycle error forms apart. With
/// spin_deg 180 each run ends where it started, facing the same way.
struct ManoeuvrePlan {
  std::size_t runs = 10;
  double speed_mps = 0.3;
  double distance_m = 4.0;
  double spin_deg = 180.0;
  double spin_rate_degps = 40.0;
  double fast_spin_degps = 120.0;
  /// The robot's seconds per second of the base's clock: p3at_sim's
  /// --speedup over ARCOS (rows are stamped in the robot's time), else 1.
  double speedup = 1.0;
};

/// `flags` for a mission robot: its max_speed_mps and its first Spin's rate
/// (the runs also drive half of each), so that it is calibrated at the
/// speeds its mission uses (issue 13 item 9).
ManoeuvrePlan plan_for_robot(const mission::RobotSpec& robot, ManoeuvrePlan flags);

/// The true pose now, if known. `at_rest` is true at a manoeuvre's first and
/// last rows (a tape measure can only measure a robot standing still).
using TruthProbe = std::function<std::optional<verifier::TruePose>(bool at_rest)>;

/// The base refused, stalled, lost its link or never finished a manoeuvre.
class DriveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Drives `plan` on `base` and appends one Manoeuvre per manoeuvre to `out`,
/// numbered from `next_id` (advanced). Throws DriveError.
void drive_manoeuvres(hal::DriveBase& base, const std::string& robot, const ManoeuvrePlan& plan,
                      const TruthProbe& truth, std::int64_t& next_id, std::vector<verifier::Manoeuvre>& out);

}  // namespace p3at::vipars
