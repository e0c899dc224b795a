#include "engine/sonar_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace p3at::verifier::engine {
namespace {

constexpr double kHalfLengthM = kBodyHalfLengthM;
constexpr double kHalfWidthM = kBodyHalfWidthM;

double point_segment_distance(double px, double py, const Segment& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((px - s.x0) * dx + (py - s.y0) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (s.x0 + t * dx), py - (s.y0 + t * dy));
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

std::array<Segment, 4> body_segments(double x_m, double y_m, double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  auto corner = [&](double bx, double by) { return std::array<double, 2>{x_m + c * bx - s * by, y_m + s * bx + c * by}; };
  const auto a = corner(kHalfLengthM, kHalfWidthM), b = corner(-kHalfLengthM, kHalfWidthM);
  const auto d = corner(-kHalfLengthM, -kHalfWidthM), e = corner(kHalfLengthM, -kHalfWidthM);
  return {Segment{a[0], a[1], b[0], b[1]}, Segment{b[0], b[1], d[0], d[1]}, Segment{d[0], d[1], e[0], e[1]},
          Segment{e[0], e[1], a[0], a[1]}};
}

std::array<double, exec::kP3atSonarCount> sonar_ranges(const std::vector<Segment>& segments, double x_m, double y_m,
                                                       double theta_rad, double max_range_m) {
  // The ring's directions in the robot frame, computed once (the executive's
  // table): each call then needs one sine and cosine, not sixteen (this is
  // the verifier's hot loop).
  const auto& directions = exec::sonar_facings();
  std::array<double, exec::kP3atSonarCount> ranges{};
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  for (std::size_t i = 0; i < exec::kP3atSonarCount; ++i) {
    const exec::SonarPose& sonar = exec::kP3atSonars[i];
    const double ox = x_m + c * sonar.x_m - s * sonar.y_m;
    const double oy = y_m + s * sonar.x_m + c * sonar.y_m;
    const double cx = c * directions[i][0] - s * directions[i][1];
    const double cy = s * directions[i][0] + c * directions[i][1];
    double best = max_range_m;
    for (const Segment& seg : segments) {
      const double t = ray_hit(ox, oy, cx, cy, seg, best);
      if (t >= 0.0 && t < best) best = t;
    }
    ranges[i] = best;
  }
  return ranges;
}

}  // namespace p3at::verifier::engine
