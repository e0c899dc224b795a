#include "p3at/sim/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "p3at/common/segment_box.hpp"

namespace p3at::sim {

double wrap_angle_any(double angle_rad) {
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
  double nearest = max_range_m;
  bool hit = false;
  for (const Segment& s : segments) hit = ray_hit(origin, unit_direction, s, nearest) || hit;
  if (!hit) return std::nullopt;
  return nearest;
}

namespace {

// Whether the segment p0->p1 meets the box |x| <= hx, |y| <= hy (the
// verifier's body_contact holds its paths at walls by the same test).
bool segment_touches_box(Vec2 p0, Vec2 p1, double hx, double hy) {
  return segment_meets_centred_box(p0.x, p0.y, p1.x, p1.y, hx, hy);
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

Box make_box(Vec2 centre, double cos_theta, double sin_theta, double length_m, double width_m) {
  return Box{centre, cos_theta, sin_theta, length_m / 2.0, width_m / 2.0, std::hypot(length_m, width_m) / 2.0};
}

Box to_box(const Footprint& footprint) {
  return make_box({footprint.pose.x_m, footprint.pose.y_m}, std::cos(footprint.pose.theta_rad),
                  std::sin(footprint.pose.theta_rad), footprint.length_m, footprint.width_m);
}

bool intersects(const Footprint& footprint, const Segment& segment) { return intersects(to_box(footprint), segment); }

bool intersects(const Box& box, const Segment& segment) {
  // Broad phase: a segment farther from the centre than the bounding circle
  // cannot touch the box. Collision checks run every physics substep, so this
  // is on the simulator's hot path.
  if (!segment_within(box.centre, segment, box.radius_m)) return false;
  const double c = box.cos_theta;
  const double s = box.sin_theta;
  const auto local = [&](Vec2 w) {
    const double dx = w.x - box.centre.x;
    const double dy = w.y - box.centre.y;
    return Vec2{c * dx + s * dy, -s * dx + c * dy};
  };
  return segment_touches_box(local(segment.a), local(segment.b), box.half_length_m, box.half_width_m);
}

void footprint_edges(const Footprint& footprint, Segment out[4]) { box_edges(to_box(footprint), out); }

void box_edges(const Box& box, Segment out[4]) {
  const auto corner = [&](double lx, double ly) {
    return Vec2{box.centre.x + box.cos_theta * lx - box.sin_theta * ly,
                box.centre.y + box.sin_theta * lx + box.cos_theta * ly};
  };
  const double hx = box.half_length_m;
  const double hy = box.half_width_m;
  const Vec2 c[4] = {corner(hx, hy), corner(-hx, hy), corner(-hx, -hy), corner(hx, -hy)};
  for (int i = 0; i < 4; ++i) out[i] = Segment{c[i], c[(i + 1) % 4]};
}

bool intersects(const Footprint& first, const Footprint& second) { return intersects(to_box(first), to_box(second)); }

bool intersects(const Box& first, const Box& second) {
  const double reach = first.radius_m + second.radius_m;
  const double dx = first.centre.x - second.centre.x;
  const double dy = first.centre.y - second.centre.y;
  if (dx * dx + dy * dy > reach * reach) return false;  // too far apart to touch
  // Two rectangles overlap iff an edge of one touches the other, or one contains
  // the other (and then the inner one's centre is inside the outer one).
  Segment edges[4];
  box_edges(second, edges);
  for (const Segment& e : edges) {
    if (intersects(first, e)) return true;
  }
  const auto centre_inside = [](const Box& box, const Box& other) {
    const double wx = other.centre.x - box.centre.x;
    const double wy = other.centre.y - box.centre.y;
    const double lx = box.cos_theta * wx + box.sin_theta * wy;
    const double ly = -box.sin_theta * wx + box.cos_theta * wy;
    return std::abs(lx) <= box.half_length_m && std::abs(ly) <= box.half_width_m;
  };
  return centre_inside(first, second) || centre_inside(second, first);
}

}  // namespace p3at::sim
