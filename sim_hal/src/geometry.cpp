#include "p3at/sim/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace p3at::sim {

double wrap_angle(double angle_rad) {
  const double two_pi = 2.0 * std::numbers::pi;
  double a = std::fmod(angle_rad, two_pi);
  if (a <= -std::numbers::pi) a += two_pi;
  if (a > std::numbers::pi) a -= two_pi;
  return a;
}

Vec2 to_world(const Pose& frame, Vec2 local) {
  const double c = std::cos(frame.theta_rad);
  const double s = std::sin(frame.theta_rad);
  return {frame.x_m + c * local.x - s * local.y, frame.y_m + s * local.x + c * local.y};
}

Vec2 to_local(const Pose& frame, Vec2 world) {
  const double c = std::cos(frame.theta_rad);
  const double s = std::sin(frame.theta_rad);
  const double dx = world.x - frame.x_m;
  const double dy = world.y - frame.y_m;
  return {c * dx + s * dy, -s * dx + c * dy};
}

std::optional<double> ray_cast(Vec2 origin, double heading_rad, std::span<const Segment> segments,
                               double max_range_m) {
  return ray_cast_dir(origin, {std::cos(heading_rad), std::sin(heading_rad)}, segments, max_range_m);
}

std::optional<double> ray_cast_dir(Vec2 origin, Vec2 unit_direction, std::span<const Segment> segments,
                                   double max_range_m) {
  const double dx = unit_direction.x;
  const double dy = unit_direction.y;
  std::optional<double> best;
  for (const Segment& s : segments) {
    const double ex = s.b.x - s.a.x;
    const double ey = s.b.y - s.a.y;
    // Solve origin + t*d = a + u*e for t >= 0, u in [0, 1].
    const double denom = dx * ey - dy * ex;
    const double wx = s.a.x - origin.x;
    const double wy = s.a.y - origin.y;
    if (std::abs(denom) < 1e-12) continue;  // parallel: a grazing ray returns no echo
    const double t = (wx * ey - wy * ex) / denom;
    const double u = (wx * dy - wy * dx) / denom;
    if (t < 0.0 || u < 0.0 || u > 1.0 || t > max_range_m) continue;
    if (!best || t < *best) best = t;
  }
  return best;
}

namespace {

// Liang-Barsky clipping of the segment p0->p1 against the box |x| <= hx, |y| <= hy.
bool segment_touches_box(Vec2 p0, Vec2 p1, double hx, double hy) {
  double t0 = 0.0;
  double t1 = 1.0;
  const double d[2] = {p1.x - p0.x, p1.y - p0.y};
  const double p[4] = {-d[0], d[0], -d[1], d[1]};
  const double q[4] = {p0.x + hx, hx - p0.x, p0.y + hy, hy - p0.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, r);
    } else {
      t1 = std::min(t1, r);
    }
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

// Squared distance from point p to the segment a-b.
double distance_sq_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const double ex = b.x - a.x;
  const double ey = b.y - a.y;
  const double len_sq = ex * ex + ey * ey;
  double t = len_sq > 0.0 ? ((p.x - a.x) * ex + (p.y - a.y) * ey) / len_sq : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double dx = a.x + t * ex - p.x;
  const double dy = a.y + t * ey - p.y;
  return dx * dx + dy * dy;
}

namespace {

// Half the diagonal, squared: no part of the box is farther than this from its centre.
double half_diagonal_sq(const Footprint& f) { return (f.length_m * f.length_m + f.width_m * f.width_m) / 4.0; }

}  // namespace

bool intersects(const Footprint& footprint, const Segment& segment) {
  // Broad phase without trigonometry: a segment farther from the centre than
  // the half-diagonal cannot touch the box. Collision checks run every physics
  // substep against every wall, so this is the simulator's hot path.
  const Vec2 centre{footprint.pose.x_m, footprint.pose.y_m};
  if (distance_sq_to_segment(centre, segment.a, segment.b) > half_diagonal_sq(footprint)) return false;
  const double c = std::cos(footprint.pose.theta_rad);
  const double s = std::sin(footprint.pose.theta_rad);
  const auto local = [&](Vec2 w) {
    const double dx = w.x - centre.x;
    const double dy = w.y - centre.y;
    return Vec2{c * dx + s * dy, -s * dx + c * dy};
  };
  return segment_touches_box(local(segment.a), local(segment.b), footprint.length_m / 2.0, footprint.width_m / 2.0);
}

void footprint_edges(const Footprint& footprint, Segment out[4]) {
  const double hx = footprint.length_m / 2.0;
  const double hy = footprint.width_m / 2.0;
  const Vec2 c[4] = {to_world(footprint.pose, {hx, hy}), to_world(footprint.pose, {-hx, hy}),
                     to_world(footprint.pose, {-hx, -hy}), to_world(footprint.pose, {hx, -hy})};
  for (int i = 0; i < 4; ++i) out[i] = Segment{c[i], c[(i + 1) % 4]};
}

bool intersects(const Footprint& first, const Footprint& second) {
  const double reach = std::sqrt(half_diagonal_sq(first)) + std::sqrt(half_diagonal_sq(second));
  const double dx = first.pose.x_m - second.pose.x_m;
  const double dy = first.pose.y_m - second.pose.y_m;
  if (dx * dx + dy * dy > reach * reach) return false;  // too far apart to touch
  // Two rectangles overlap iff an edge of one touches the other, or one contains
  // the other (and then the inner one's centre is inside the outer one).
  Segment edges[4];
  footprint_edges(second, edges);
  for (const Segment& e : edges) {
    if (intersects(first, e)) return true;
  }
  const auto centre_inside = [](const Footprint& box, const Footprint& other) {
    const Vec2 c = to_local(box.pose, {other.pose.x_m, other.pose.y_m});
    return std::abs(c.x) <= box.length_m / 2.0 && std::abs(c.y) <= box.width_m / 2.0;
  };
  return centre_inside(first, second) || centre_inside(second, first);
}

}  // namespace p3at::sim
