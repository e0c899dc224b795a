#pragma once
/// The duration of one exit of a motion state whose NOISE direction was held
/// for the whole state (no redraw before the paths fired): the held
/// quadrature's paths, one per equally spaced NOISE direction, are samples of
/// the crossing time T(phi) as a function of the direction phi, which is
/// uniform on the circle. The duration's distribution is that of T(phi) over
/// the circle (docs/verifier.md, "The held durations over the circle").

#include <cstddef>
#include <vector>

#include "engine/noise_segments.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {

/// One start point's circle of NOISE directions under its first draw.
struct HeldCircle {
  /// The path of direction j that fired this exit (nullptr where direction
  /// j fired another exit, got stuck or was still running).
  std::vector<const FinishedPath*> fired;
  /// Direction j was still running when the NOISE was redrawn, at
  /// `draw_end_cycles` from the entry: its crossing lies beyond that.
  std::vector<bool> running;
  double draw_end_cycles = 0.0;
  /// The circle's directions' angles, the boundaries between their arcs and
  /// the probes, when it was probed (one of NoiseQuadrature::probed, which
  /// outlives this; null otherwise), and the exit this duration is of
  /// (probes that fired it are samples of T).
  const ProbedCircle* probed = nullptr;
  std::size_t exit = 0;
};

/// Between two neighbouring directions that both fired the exit, T is
/// interpolated (cubic Hermite: monotone where the samples keep rising or
/// falling, through the extreme where they turn) and each half of the arc
/// belongs to its nearer direction's weight. Toward a
/// neighbour still running at the redraw, T is interpolated toward the
/// later of the redraw and the node's own trend carried on (the runs
/// between fire later and later as they near the running direction); toward
/// one that fired another exit or got stuck, the half arc stays at the
/// node's T. Each point of the arc then fires at the check its crossing
/// falls before, spread by the odometry's random error (check_shares), and
/// the checks' masses (at whole cycles of `cycle_s`, each a cycle wide on a
/// circle of three or more directions) are reduced to `max_components`.
///
/// On a probed circle each fired direction's weight is its arc (which may
/// reach past the midpoint toward a neighbour that did not fire), and T is
/// interpolated along the arc through the probes inside it that fired this
/// exit, as between neighbours (node slopes for unequal spacing, Fritsch and
/// Butland's weighted harmonic mean); past the last of them, toward the
/// arc's boundary, by the rules above. Without the probes, an arc that
/// reached toward a running neighbour was given times rising toward the
/// redraw, where the probes inside it fired within a few seconds of the
/// direction: on fresh gen_7719's first leg (NOISE held 48 s) P(t <= 36 s)
/// was 0.124 against 1,000 runs' 0.184 (now 0.173;
/// tests/unit/verifier/test_first_draw_arcs_cli.cpp).
Mixture1 held_duration(const HeldCircle& circle, double cycle_s, std::size_t max_components);

}  // namespace p3at::verifier::engine
