#include "engine/body_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "p3at/common/segment_box.hpp"

namespace p3at::verifier::engine {
namespace {

// How deep a segment that meets the rectangle reaches into it: the largest
// distance from a point of the segment to the rectangle's outline, inside.
// Inside, that distance is min(hx - |x|, hy - |y|), the least of four linear
// functions of t along the segment (concave), so its largest value on [0, 1]
// is at an end or where two of the four cross.
double segment_depth(double ax, double ay, double bx, double by, double hx, double hy) {
  const double dx = bx - ax, dy = by - ay;
  // f_i(t) = c_i + s_i t: hx - x, hx + x, hy - y, hy + y.
  const double c[4] = {hx - ax, hx + ax, hy - ay, hy + ay};
  const double s[4] = {-dx, dx, -dy, dy};
  const auto inner = [&](double t) {
    double m = c[0] + s[0] * t;
    for (int i = 1; i < 4; ++i) m = std::min(m, c[i] + s[i] * t);
    return m;
  };
  double best = std::max(inner(0.0), inner(1.0));
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      if (s[i] == s[j]) continue;
      const double t = (c[j] - c[i]) / (s[i] - s[j]);
      if (t > 0.0 && t < 1.0) best = std::max(best, inner(t));
    }
  }
  return std::max(best, 0.0);
}

/// How the body at a pose meets the segments: the deepest any reaches into
/// it (negative when none meets it), and the least distance from its centre
/// to one that does.
struct Overlap {
  double depth = -1.0;
  double centre_m = std::numeric_limits<double>::infinity();
};

Overlap body_overlap(const std::vector<Segment>& segments, double x_m, double y_m, double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  Overlap o;
  for (const Segment& g : segments) {
    // Broad phase: the segment's bounding box beyond the body's circle.
    const auto [box_dx, box_dy] = offset_to_box(x_m, y_m, g);
    if (surely_longer(box_dx, box_dy, kBodyHalfDiagonalM)) continue;
    const double ax = c * (g.x0 - x_m) + s * (g.y0 - y_m), ay = -s * (g.x0 - x_m) + c * (g.y0 - y_m);
    const double bx = c * (g.x1 - x_m) + s * (g.y1 - y_m), by = -s * (g.x1 - x_m) + c * (g.y1 - y_m);
    if (segment_meets_centred_box(ax, ay, bx, by, kBodyHalfLengthM, kBodyHalfWidthM)) {
      o.depth = std::max(o.depth, segment_depth(ax, ay, bx, by, kBodyHalfLengthM, kBodyHalfWidthM));
      o.centre_m = std::min(o.centre_m, point_segment_distance(x_m, y_m, g));
    }
  }
  return o;
}

}  // namespace

bool body_touches(const std::vector<Segment>& segments, double x_m, double y_m, double theta_rad) {
  return body_overlap(segments, x_m, y_m, theta_rad).depth >= 0.0;
}

double contact_reach_m(double top_speed_mps, double top_rot_radps, double cycle_s) {
  const double corner_travel = (std::abs(top_speed_mps) + std::abs(top_rot_radps) * kBodyHalfDiagonalM) * cycle_s;
  return kBodyHalfDiagonalM + corner_travel + 0.01;
}

CycleIncrement step_cycle_against(BaseState& base, double command_trans_mps, double command_rot_radps,
                                  const Kinematics& kinematics, const std::vector<Segment>& segments,
                                  const double error_mean[3], bool* stalled) {
  if (stalled) *stalled = false;
  const auto overlap = [&](const BaseState& q) {
    return body_overlap(segments, q.x_m + error_mean[0], q.y_m + error_mean[1], q.theta_rad + error_mean[2]);
  };
  Overlap now = overlap(base);
  return step_cycle_held(base, command_trans_mps, command_rot_radps, kinematics, [&](const BaseState& next) {
    const Overlap then = overlap(next);
    // Clear, the substep is the simulator's: held on any contact. Already
    // inside (see the header), held only when it drives the centre in and
    // the body deeper: turning on the spot and backing out stay free.
    const bool held = now.depth < 0.0 ? then.depth >= 0.0
                                      : then.depth > now.depth + 1e-12 && then.centre_m < now.centre_m - 1e-12;
    if (held) {
      if (stalled) *stalled = true;
    } else {
      now = then;
    }
    return held;
  });
}

}  // namespace p3at::verifier::engine
