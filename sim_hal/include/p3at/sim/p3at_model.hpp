#pragma once
/// Fixed facts about a Pioneer 3-AT (docs/arcos-protocol.md §8, ARIA's p3at.p).

#include <array>
#include <cstdint>

#include "p3at/sim/geometry.hpp"

namespace p3at::sim {

/// Footprint: 626 mm long, 505 mm wide, centred on the odometry origin.
inline constexpr double kP3atLengthM = 0.626;
inline constexpr double kP3atWidthM = 0.505;

/// The track the firmware assumes when it turns wheel speeds into rotation:
/// DiffConvFactor 0.0034 → rot = (right - left) × 0.0034 / 2 → 2 / 0.0034 mm ≈ 588 mm.
inline constexpr double kNominalTrackM = 2.0 / 0.0034 / 1000.0;

/// One controller cycle (SIP period), microseconds.
inline constexpr std::int64_t kCycleUs = 100'000;

/// Sonar transducer pose on the robot: position (metres, robot frame) and heading.
struct SonarPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
};

inline constexpr int kP3atSonarCount = 16;

/// The 16 sonars of the P3-AT, in sonar-number order.
inline constexpr std::array<SonarPose, kP3atSonarCount> kP3atSonars{{
    {0.147, 0.136, 90},    {0.193, 0.119, 50},    {0.227, 0.079, 30},    {0.245, 0.027, 10},
    {0.245, -0.027, -10},  {0.227, -0.079, -30},  {0.193, -0.119, -50},  {0.147, -0.136, -90},
    {-0.144, -0.136, -90}, {-0.189, -0.119, -130}, {-0.223, -0.079, -150}, {-0.241, -0.027, -170},
    {-0.241, 0.027, 170},  {-0.223, 0.079, 150},  {-0.189, 0.119, 130},  {-0.144, 0.136, 90},
}};

}  // namespace p3at::sim
