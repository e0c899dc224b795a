#pragma once
/// Where on the circle of NOISE directions one outcome of the first draw
/// gives way to another, found by bisection, and each quadrature direction's
/// share of the circle from it.
///
/// Why: the first draw's direction is uniform on the circle and the
/// quadrature steps `directions` equally spaced paths (engine/noise_segments),
/// each weighing 1 / directions. What a path does under that draw (fires an
/// exit, is still running at the redraw, is pinned for good) is a step
/// function of the angle, so each share came out a multiple of 1/8. Fresh
/// generated gen_7719 (seeds 7681-7720): its first leg holds NOISE 48 s
/// (gain 0.235) past a concave corner; one of the eight directions got
/// through under the first draw (0.125) where 2,000 runs finished 0.216 by
/// 40 s, and the rest waited for a redraw: the time curve stood 0.09 too low
/// from 33 s to the next lump at 50 s (now 0.219 by 45 s; the 1,000 runs of
/// tests/unit/verifier/test_first_draw_arcs_cli.cpp 0.234).
///
/// So where two neighbouring directions' outcomes differ, the angle between
/// them is bisected `depth` times (each probe one path stepped under the
/// first draw, as the quadrature steps it) and the boundary is put at the
/// middle of the last bracket; where they agree, at the midpoint (the equal
/// shares). A direction's share is the arc between its two boundaries. The
/// paths themselves are not moved: each stands for its whole arc.

#include <cstddef>
#include <functional>
#include <vector>

namespace p3at::verifier::engine {

/// A whole turn of the circle of directions, in radians.
inline constexpr double kTurnRad = 2.0 * 3.14159265358979323846;

/// What a path does under the first draw (a transition fired is its index + 2).
using DrawOutcome = long;
inline constexpr DrawOutcome kDrawPinned = 0;   ///< stood still for good or reached the cycle cap
inline constexpr DrawOutcome kDrawRunning = 1;  ///< still moving at the redraw
inline DrawOutcome draw_fired(std::size_t transition) { return static_cast<DrawOutcome>(transition) + 2; }

/// The outcome of one path stepped from the circle's start at this angle (radians).
using DrawProbe = std::function<DrawOutcome(double angle_rad)>;

struct DirectionArcLimits {
  std::size_t depth = 3;        ///< bisections per boundary: located to 1/2^depth of the spacing
  std::size_t max_probes = 16;  ///< per circle (boundaries beyond the budget stay at the midpoint)
};

/// Each direction's share of the circle (summing to 1), for `angles`
/// increasing and less than a turn apart end to end, with their `outcomes`.
/// Fewer than two directions, or all agreeing: the equal shares, no probe.
/// `boundaries` (when given and probes were made): boundary j, between
/// direction j and j + 1, in the angles' radians (the last one lies between
/// angles[n - 1] and angles[0] + 2 pi), so direction j's arc runs from
/// boundary j - 1 to boundary j, with boundary -1 = boundary n - 1 - 2 pi.
std::vector<double> direction_arcs(const std::vector<double>& angles, const std::vector<DrawOutcome>& outcomes,
                                   const DrawProbe& probe, const DirectionArcLimits& limits, std::size_t& probes_made,
                                   std::vector<double>* boundaries = nullptr);

}  // namespace p3at::verifier::engine
