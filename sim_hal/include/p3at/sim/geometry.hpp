#pragma once
/// Plane geometry for the simulated world: points, wall segments, oriented
/// rectangles (robot footprints), ray casting. Metres and radians throughout.

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

/// An angle wrapped to (-pi, pi].
double wrap_angle(double angle_rad);

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

/// A robot footprint: a rectangle centred on `pose`, `length_m` along the heading,
/// `width_m` across it.
struct Footprint {
  Pose pose;
  double length_m = 0.0;
  double width_m = 0.0;
};

/// Squared distance from point `p` to the segment a-b.
double distance_sq_to_segment(Vec2 p, Vec2 a, Vec2 b);

/// True when the segment touches or crosses the (closed) rectangle.
bool intersects(const Footprint& footprint, const Segment& segment);

/// True when the two rectangles overlap or touch.
bool intersects(const Footprint& first, const Footprint& second);

/// The four edges of a footprint, world frame, for ray casting against other robots.
void footprint_edges(const Footprint& footprint, Segment out[4]);

}  // namespace p3at::sim
