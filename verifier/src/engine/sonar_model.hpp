#pragma once
/// The sensor and environment model: what the Pioneer's sonar ring reads at a
/// true pose, given the walls of the map and the teammates' bodies, each sonar
/// taken as a single ray (its mean reading). The executive turns the readings
/// into AVOID_OBSTACLES' obstacle points (exec::sonar_obstacles), so the
/// verifier's obstacle avoidance is the executive's own.

#include <array>
#include <cmath>
#include <vector>

#include "p3at/executive/sonar.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::engine {

struct Segment {
  double x0, y0, x1, y1;
};

/// The P3-AT's footprint (626 x 505 mm), as the simulator and the bridge use it.
inline constexpr double kBodyHalfLengthM = 0.313;
inline constexpr double kBodyHalfWidthM = 0.2525;
/// The farthest the footprint's outline is from its centre.
inline const double kBodyHalfDiagonalM = std::hypot(kBodyHalfLengthM, kBodyHalfWidthM);

/// The segments a robot can see while it moves around `from`..`to` (walls and
/// bodies within sonar range of that stretch), so each ray tests few segments.
std::vector<Segment> segments_near(const std::vector<Segment>& all, double from_x, double from_y, double to_x,
                                   double to_y, double reach_m);

/// Whether the offset (dx, dy) is surely longer than limit_m: its square
/// exceeds limit_m squared by more than rounding can account for (a part in
/// 1e9 of slack). Never true of an offset whose length (std::hypot) is within
/// limit_m, so a pre-filter built on it passes over only what an exact test
/// would reject; and without a square root, for the hot loops.
inline bool surely_longer(double dx, double dy, double limit_m) {
  return dx * dx + dy * dy > limit_m * limit_m * (1.0 + 1e-9);
}

/// The distance from (px, py) to the segment.
double point_segment_distance(double px, double py, const Segment& s);

/// The offset from (px, py) to the segment's bounding box: never longer than
/// to the segment itself, and without a division, so a cheap first test that
/// a segment is out of reach (with surely_longer, the question every
/// pre-filter here asks).
std::array<double, 2> offset_to_box(double px, double py, const Segment& s);

/// The distance from (x, y) to the nearest segment (infinity if none).
double nearest_distance(const std::vector<Segment>& segments, double x_m, double y_m);

/// Whether some segment is within reach_m of (x, y): the same answer as
/// nearest_distance(segments, x, y) <= reach_m, without its square roots
/// (asked every cycle of every walker).
bool any_within(const std::vector<Segment>& segments, double x_m, double y_m, double reach_m);

/// The four sides of a Pioneer 3-AT body at pose (x, y, theta).
std::array<Segment, 4> body_segments(double x_m, double y_m, double theta_rad);

/// Ranges of the 16 sonars for a robot at the true pose (x, y, theta); a ray
/// that hits nothing within max_range_m reads max_range_m ("nothing seen").
/// With cast_m below max_range_m, rays are cast only that far and what lies
/// beyond reads max_range_m too: for a caller to which nothing that far can
/// matter (AVOID_OBSTACLES beyond its reach), and much cheaper.
std::array<double, exec::kP3atSonarCount> sonar_ranges(const std::vector<Segment>& segments, double x_m, double y_m,
                                                       double theta_rad, double max_range_m, double cast_m);

inline std::array<double, exec::kP3atSonarCount> sonar_ranges(const std::vector<Segment>& segments, double x_m,
                                                              double y_m, double theta_rad, double max_range_m) {
  return sonar_ranges(segments, x_m, y_m, theta_rad, max_range_m, max_range_m);
}

}  // namespace p3at::verifier::engine
