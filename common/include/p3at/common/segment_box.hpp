#pragma once
/// Whether a segment meets a rectangle centred on the origin: the footprint
/// test of a robot's body against a wall, in the body's own frame. One
/// function for the simulator's collisions (sim_hal geometry) and the
/// verifier's stalls (verifier engine/body_contact), so the two hold a body
/// at a wall by the same arithmetic.

#include <algorithm>

namespace p3at {

/// Liang-Barsky clipping: whether the segment (ax, ay)-(bx, by) meets the
/// rectangle |x| <= hx, |y| <= hy (its outline counts as inside).
inline bool segment_meets_centred_box(double ax, double ay, double bx, double by, double hx, double hy) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = bx - ax, dy = by - ay;
  // Each side: the direction's component p and the room q on that side (p t <= q).
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax + hx, hx - ax, ay + hy, hy - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;  // parallel to this side and outside it
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

}  // namespace p3at
