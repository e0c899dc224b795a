#pragma once
/// The Pioneer 3-AT's sonar ring as AVOID_OBSTACLES' obstacle source: each valid
/// range becomes one obstacle point in the frame of the given robot pose.
/// Header-only and generic over the scalar type S like schemas.hpp.

#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "p3at/executive/schemas.hpp"

namespace p3at::exec {

/// One transducer: its position on the robot (metres, +x forward, +y left) and
/// the direction it faces (degrees counter-clockwise from forward).
struct SonarPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_deg = 0.0;
};

inline constexpr std::size_t kP3atSonarCount = 16;

/// The P3-AT's 16 sonars, numbered as in ARIA's p3at.p (docs/arcos-protocol.md §8).
inline constexpr std::array<SonarPose, kP3atSonarCount> kP3atSonars{{
    {0.147, 0.136, 90.0},    {0.193, 0.119, 50.0},    {0.227, 0.079, 30.0},    {0.245, 0.027, 10.0},
    {0.245, -0.027, -10.0},  {0.227, -0.079, -30.0},  {0.193, -0.119, -50.0},  {0.147, -0.136, -90.0},
    {-0.144, -0.136, -90.0}, {-0.189, -0.119, -130.0}, {-0.223, -0.079, -150.0}, {-0.241, -0.027, -170.0},
    {-0.241, 0.027, 170.0},  {-0.223, 0.079, 150.0},  {-0.189, 0.119, 130.0},  {-0.144, 0.136, 90.0},
}};

/// The P3-AT's sonar range (ARIA's default maximum): a reading at or beyond it means
/// "nothing seen".
inline constexpr double kP3atSonarMaxRangeM = 5.0;

/// Up to 16 obstacle points, without allocating.
template <class S>
struct SonarObstacles {
  std::array<Vec2<S>, kP3atSonarCount> points{};
  std::size_t count = 0;

  std::span<const Vec2<S>> view() const { return std::span<const Vec2<S>>(points.data(), count); }
};

/// Each sonar's facing as (cos, sin) of its heading, computed once: the
/// conversion below runs every control cycle (and millions of times in the
/// verifier's within-state model), and 32 trigonometric calls a cycle for
/// constants were a tenth of the verifier's time.
inline const std::array<std::array<double, 2>, kP3atSonarCount>& sonar_facings() {
  static const std::array<std::array<double, 2>, kP3atSonarCount> facings = [] {
    constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
    std::array<std::array<double, 2>, kP3atSonarCount> f{};
    for (std::size_t i = 0; i < kP3atSonarCount; ++i) {
      f[i] = {std::cos(kP3atSonars[i].heading_deg * kDegToRad), std::sin(kP3atSonars[i].heading_deg * kDegToRad)};
    }
    return f;
  }();
  return facings;
}

/// Converts the ring's ranges (metres, indexed by sonar number) into obstacle
/// points in the frame `robot_pose` is expressed in: point = pose ⊕ (sonar
/// position + range × sonar direction). Readings that are negative (none yet),
/// not finite, or at/over `max_range_m` are skipped.
template <class S>
SonarObstacles<S> sonar_obstacles(std::span<const double, kP3atSonarCount> ranges_m, const Pose<S>& robot_pose,
                                  double max_range_m = kP3atSonarMaxRangeM) {
  using std::cos;
  using std::sin;
  SonarObstacles<S> out;
  const S c = S(cos(robot_pose.theta_rad));
  const S s = S(sin(robot_pose.theta_rad));
  const auto& facings = sonar_facings();
  for (std::size_t i = 0; i < kP3atSonarCount; ++i) {
    const double range_m = ranges_m[i];
    if (!std::isfinite(range_m) || range_m < 0.0 || range_m >= max_range_m) continue;
    const SonarPose& sonar = kP3atSonars[i];
    const double bx = sonar.x_m + range_m * facings[i][0];
    const double by = sonar.y_m + range_m * facings[i][1];
    out.points[out.count] = Vec2<S>{S(robot_pose.x_m + c * bx - s * by), S(robot_pose.y_m + s * bx + c * by)};
    ++out.count;
  }
  return out;
}

}  // namespace p3at::exec
