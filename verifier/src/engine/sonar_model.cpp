#include "engine/sonar_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace p3at::verifier::engine {
namespace {

constexpr double kHalfLengthM = kBodyHalfLengthM;
constexpr double kHalfWidthM = kBodyHalfWidthM;

// The offset (dx, dy) from (px, py) to the segment's nearest point.
std::array<double, 2> offset_to_segment(double px, double py, const Segment& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((px - s.x0) * dx + (py - s.y0) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return {px - (s.x0 + t * dx), py - (s.y0 + t * dy)};
}

// Whether a point at offset (dx, dy) is within reach_m (reach_m > 0, of a
// size a map has), with exactly the answer of std::hypot(dx, dy) <= reach_m.
// The squared distance settles every point clearly inside or outside (its
// rounding is a few parts in 1e16, the slack a part in 1e9), and only a point
// within a hair of the edge pays for the exact, slow hypot.
bool offset_within(double dx, double dy, double reach_m) {
  if (dx * dx + dy * dy < reach_m * reach_m * (1.0 - 1e-9)) return true;
  if (surely_longer(dx, dy, reach_m)) return false;
  return std::hypot(dx, dy) <= reach_m;
}

// The farthest a sonar of the ring sits from the robot's centre.
double ring_radius_m() {
  double r = 0.0;
  for (const exec::SonarPose& sonar : exec::kP3atSonars) r = std::max(r, std::hypot(sonar.x_m, sonar.y_m));
  return r;
}

// Distance along the ray (ox, oy) + t (cx, cy) to the segment when it is
// below `best`, else a negative value or one at least `best`. The same
// arithmetic as solving for t and u and testing t >= 0, 0 <= u <= 1, in an
// order that leaves most segments (behind the sonar, or farther than what it
// already sees) before the divisions: the result is the same to the bit.
double ray_hit(double ox, double oy, double cx, double cy, const Segment& s, double best) {
  const double ex = s.x1 - s.x0, ey = s.y1 - s.y0;
  const double denom = cx * ey - cy * ex;
  if (std::abs(denom) < 1e-12) return -1.0;
  const double wx = s.x0 - ox, wy = s.y0 - oy;
  const double t_num = wx * ey - wy * ex;
  // t = t_num / denom < 0 exactly when the two have opposite signs and t_num is not 0.
  if (t_num != 0.0 && std::signbit(t_num) != std::signbit(denom)) return -1.0;
  const double t = t_num / denom;
  if (!(t < best)) return t;
  const double u = (wx * cy - wy * cx) / denom;
  if (u < 0.0 || u > 1.0) return -1.0;
  return t;
}

}  // namespace

double point_segment_distance(double px, double py, const Segment& s) {
  const auto [dx, dy] = offset_to_segment(px, py, s);
  return std::hypot(dx, dy);
}

std::array<double, 2> offset_to_box(double px, double py, const Segment& s) {
  return {std::max({std::min(s.x0, s.x1) - px, px - std::max(s.x0, s.x1), 0.0}),
          std::max({std::min(s.y0, s.y1) - py, py - std::max(s.y0, s.y1), 0.0})};
}

std::vector<Segment> segments_near(const std::vector<Segment>& all, double from_x, double from_y, double to_x,
                                   double to_y, double reach_m) {
  // A segment is near if either end of the stretch, or its middle, is within
  // reach of it, or it crosses the stretch: a cheap, conservative filter.
  const Segment stretch{from_x, from_y, to_x, to_y};
  const double half = std::hypot(to_x - from_x, to_y - from_y) / 2.0;
  const double mx = (from_x + to_x) / 2.0, my = (from_y + to_y) / 2.0;
  std::vector<Segment> near;
  for (const Segment& s : all) {
    const double d_mid = point_segment_distance(mx, my, s);
    const bool close = d_mid <= reach_m + half || point_segment_distance(s.x0, s.y0, stretch) <= reach_m ||
                       point_segment_distance(s.x1, s.y1, stretch) <= reach_m;
    if (close) near.push_back(s);
  }
  return near;
}

double nearest_distance(const std::vector<Segment>& segments, double x_m, double y_m) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments) best = std::min(best, point_segment_distance(x_m, y_m, s));
  return best;
}

bool any_within(const std::vector<Segment>& segments, double x_m, double y_m, double reach_m) {
  // Outside the sizes offset_within is exact for, ask the plain question.
  if (!(reach_m > 1e-100 && reach_m < 1e100)) return nearest_distance(segments, x_m, y_m) <= reach_m;
  for (const Segment& s : segments) {
    const auto [bx, by] = offset_to_box(x_m, y_m, s);
    if (surely_longer(bx, by, reach_m)) continue;
    const auto [dx, dy] = offset_to_segment(x_m, y_m, s);
    if (offset_within(dx, dy, reach_m)) return true;
  }
  return false;
}

std::array<Segment, 4> body_segments(double x_m, double y_m, double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  auto corner = [&](double bx, double by) { return std::array<double, 2>{x_m + c * bx - s * by, y_m + s * bx + c * by}; };
  const auto a = corner(kHalfLengthM, kHalfWidthM), b = corner(-kHalfLengthM, kHalfWidthM);
  const auto d = corner(-kHalfLengthM, -kHalfWidthM), e = corner(kHalfLengthM, -kHalfWidthM);
  return {Segment{a[0], a[1], b[0], b[1]}, Segment{b[0], b[1], d[0], d[1]}, Segment{d[0], d[1], e[0], e[1]},
          Segment{e[0], e[1], a[0], a[1]}};
}

std::array<double, exec::kP3atSonarCount> sonar_ranges(const std::vector<Segment>& segments, double x_m, double y_m,
                                                       double theta_rad, double max_range_m, double cast_m) {
  // The ring's directions in the robot frame, computed once (the executive's
  // table): each call then needs one sine and cosine, not sixteen (this is
  // the verifier's hot loop).
  const auto& directions = exec::sonar_facings();
  constexpr std::size_t kRays = exec::kP3atSonarCount;
  const double cast = std::min(cast_m, max_range_m);
  // Every element is written below (no zeroing: this is the hot loop).
  std::array<double, kRays> ox, oy, cx, cy, ranges;
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  for (std::size_t i = 0; i < kRays; ++i) {
    const exec::SonarPose& sonar = exec::kP3atSonars[i];
    ox[i] = x_m + c * sonar.x_m - s * sonar.y_m;
    oy[i] = y_m + s * sonar.x_m + c * sonar.y_m;
    cx[i] = c * directions[i][0] - s * directions[i][1];
    cy[i] = s * directions[i][0] + c * directions[i][1];
    ranges[i] = cast;
  }
  // A segment no ray can reach within the cast is passed over: every point
  // of one farther than the cast plus the ring's radius from the centre is
  // out of reach of every sonar. Rounding in ray_hit could move a hit by the
  // metre of slack only for a ray within about 1e-12 rad of parallel to a
  // segment (ray_hit's 1e-12 cut on the determinant, over a segment shorter
  // than kCullableM), where the plain cast's answer is itself noise. So the
  // readings are those of casting every ray at every segment, to the bit
  // (each ray still meets the segments in their order; checked on the CI
  // gate's missions and generated ones, and by test_sonar_model.cpp).
  constexpr double kCullableM = 100.0;
  static const double ring_m = ring_radius_m();
  const double cull_m = cast + ring_m + 1.0;
  const bool cull = cull_m > 1e-100 && cull_m < 1e100;
  for (const Segment& seg : segments) {
    const double ex = seg.x1 - seg.x0, ey = seg.y1 - seg.y0;
    if (cull && ex * ex + ey * ey < kCullableM * kCullableM) {
      const auto [bx, by] = offset_to_box(x_m, y_m, seg);
      if (surely_longer(bx, by, cull_m)) continue;
      const auto [dx, dy] = offset_to_segment(x_m, y_m, seg);
      if (surely_longer(dx, dy, cull_m)) continue;
    }
    for (std::size_t i = 0; i < kRays; ++i) {
      const double t = ray_hit(ox[i], oy[i], cx[i], cy[i], seg, ranges[i]);
      if (t >= 0.0 && t < ranges[i]) ranges[i] = t;
    }
  }
  for (double& range : ranges)
    if (!(range < cast)) range = max_range_m;
  return ranges;
}

}  // namespace p3at::verifier::engine
