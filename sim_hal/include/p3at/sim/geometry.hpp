#pragma once
/// Plane geometry for the simulated world: points, wall segments, oriented
/// rectangles (robot footprints), ray casting. Metres and radians throughout.
/// The few tests the physics runs hundreds of times per simulated cycle are
/// defined inline here (wrap_angle's common case, ray_hit, ray_may_hit,
/// segment_within).

#include <cmath>
#include <numbers>
#include <optional>
#include <span>

namespace p3at::sim {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

/// A wall: a line segment from `a` to `b`, metres, world frame.
struct Segment {
  Vec2 a;
  Vec2 b;
};

/// A pose in the plane: metres and radians, heading counter-clockwise from +X.
struct Pose {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

/// wrap_angle() for any angle (std::fmod first).
double wrap_angle_any(double angle_rad);

/// An angle wrapped to (-pi, pi]. An angle already in range is returned
/// unchanged without a call (the physics wraps headings every substep).
inline double wrap_angle(double angle_rad) {
  if (angle_rad > -std::numbers::pi && angle_rad <= std::numbers::pi) return angle_rad;
  return wrap_angle_any(angle_rad);
}

/// `local` (in the frame of `frame`) expressed in the world frame.
Vec2 to_world(const Pose& frame, Vec2 local);

/// `world` expressed in the frame of `frame`.
Vec2 to_local(const Pose& frame, Vec2 world);

/// Distance along the ray from `origin` in direction `heading_rad` to the first
/// segment it meets, if any is met within `max_range_m`.
std::optional<double> ray_cast(Vec2 origin, double heading_rad, std::span<const Segment> segments,
                               double max_range_m);
/// The same with the ray's unit direction given instead of its heading.
std::optional<double> ray_cast_dir(Vec2 origin, Vec2 unit_direction, std::span<const Segment> segments,
                                   double max_range_m);

/// Lowers `nearest_m` to the distance along the ray from `origin` in direction
/// `unit_direction` at which it meets `segment`, if it meets it at a distance
/// >= 0 and <= `nearest_m`, and says whether it did. A ray parallel to the
/// segment never meets it (a grazing ray returns no echo). ray_cast_dir() is
/// this over a list of segments.
inline bool ray_hit(Vec2 origin, Vec2 unit_direction, const Segment& segment, double& nearest_m) {
  const double dx = unit_direction.x;
  const double dy = unit_direction.y;
  const double ex = segment.b.x - segment.a.x;
  const double ey = segment.b.y - segment.a.y;
  // Solve origin + t*d = a + u*e for t >= 0, u in [0, 1]: t = tn / denom, u = un / denom.
  double denom = dx * ey - dy * ex;
  if (std::abs(denom) < 1e-12) return false;
  const double wx = segment.a.x - origin.x;
  const double wy = segment.a.y - origin.y;
  double tn = wx * ey - wy * ex;
  double un = wx * dy - wy * dx;
  if (denom < 0.0) {
    denom = -denom;
    tn = -tn;
    un = -un;
  }
  // Most segments a sonar ray is tested against lie behind it or beside it:
  // reject those on the signs alone and divide only for a real crossing.
  if (tn < 0.0 || un < 0.0 || un > denom) return false;
  const double t = tn / denom;
  if (t > nearest_m) return false;
  nearest_m = t;
  return true;
}

/// A robot footprint: a rectangle centred on `pose`, `length_m` along the heading,
/// `width_m` across it.
struct Footprint {
  Pose pose;
  double length_m = 0.0;
  double width_m = 0.0;
};

/// A footprint prepared for many tests: its heading as cosine and sine, its
/// half sizes and the radius of its bounding circle. The physics keeps these
/// up to date as a robot moves, so the collision tests of every substep need
/// no trigonometry.
struct Box {
  Vec2 centre;
  double cos_theta = 1.0;
  double sin_theta = 0.0;
  double half_length_m = 0.0;
  double half_width_m = 0.0;
  double radius_m = 0.0;  ///< half the diagonal: no part of the box is farther from the centre
};

/// The box of a `length_m` × `width_m` rectangle centred on `centre` with its heading's cosine and sine.
Box make_box(Vec2 centre, double cos_theta, double sin_theta, double length_m, double width_m);
/// `footprint` as a Box (one sine and cosine).
Box to_box(const Footprint& footprint);

/// Whether a ray from `origin` along `unit_direction` can meet anything in
/// `box` within `max_range_m`: a test against the box's bounding circle, a
/// cheap way to skip the box's four edges.
inline bool ray_may_hit(Vec2 origin, Vec2 unit_direction, const Box& box, double max_range_m) {
  const double cx = box.centre.x - origin.x;
  const double cy = box.centre.y - origin.y;
  const double reach = box.radius_m + 1e-9;  // slack for rounding: a "no" must be a certain miss
  const double along = cx * unit_direction.x + cy * unit_direction.y;
  if (along < -reach || along - reach > max_range_m) return false;  // wholly behind, or beyond range
  const double across = cx * unit_direction.y - cy * unit_direction.x;
  return std::abs(across) <= reach;
}

/// Squared distance from point `p` to the segment a-b.
double distance_sq_to_segment(Vec2 p, Vec2 a, Vec2 b);

/// Whether the segment comes within `radius_m` of `p` (closed): what
/// distance_sq_to_segment() <= radius² says, without its division. The
/// simulator's broad phases ask it many times per cycle.
inline bool segment_within(Vec2 p, const Segment& segment, double radius_m) {
  const double ex = segment.b.x - segment.a.x;
  const double ey = segment.b.y - segment.a.y;
  const double wx = p.x - segment.a.x;
  const double wy = p.y - segment.a.y;
  const double r_sq = radius_m * radius_m;
  const double along = wx * ex + wy * ey;  // p's projection on the segment, times its length
  if (along <= 0.0) return wx * wx + wy * wy <= r_sq;  // a is the nearest point
  const double len_sq = ex * ex + ey * ey;
  if (along >= len_sq) {  // b is the nearest point
    const double bx = p.x - segment.b.x;
    const double by = p.y - segment.b.y;
    return bx * bx + by * by <= r_sq;
  }
  const double across = wx * ey - wy * ex;  // p's distance to the line, times the length
  return across * across <= r_sq * len_sq;
}

/// True when the segment touches or crosses the (closed) rectangle.
bool intersects(const Footprint& footprint, const Segment& segment);
bool intersects(const Box& box, const Segment& segment);

/// True when the two rectangles overlap or touch.
bool intersects(const Footprint& first, const Footprint& second);
bool intersects(const Box& first, const Box& second);

/// The four edges of a footprint, world frame, for ray casting against other robots.
void footprint_edges(const Footprint& footprint, Segment out[4]);
void box_edges(const Box& box, Segment out[4]);

}  // namespace p3at::sim
