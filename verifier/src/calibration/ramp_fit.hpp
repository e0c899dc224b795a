#pragma once
// An acceleration (or deceleration) fitted on the odometric travel of the
// ramps, not on their per-cycle speeds.
//
// Why: a cycle's speed is the difference of two odometric readings, each
// rounded to a count (1 mm, 1/4096 turn on a P3-AT), so at 0.3 m/s and 0.1 s
// cycles it is known to about 0.004 m/s against steps of 0.03 m/s a cycle.
// Keeping only the cycles whose *measured* speed lies between 20 % and 80 %
// of the plateau selects on the noisy value: a cycle near either edge is kept
// when its noise points inwards, which flattens the fitted slope. On the
// simulator's robot (0.3 m/s^2) the speed slope came out 0.297, and that 1 %
// was the whole of gen_7009's error (docs/crosscheck.md). Here every row of a
// window chosen by time is kept, and the travel is fitted with the ramp's
// exact shape: rest, constant acceleration, plateau (or plateau, constant
// deceleration, rest), each ramp with its own start time and offset and one
// rate shared by all.

#include <cstddef>
#include <vector>

namespace p3at::verifier::calibration_detail {

/// One ramp's odometric travel, row by row.
struct RampTrace {
  std::vector<double> t_s;     ///< row times
  std::vector<double> travel;  ///< travel along the command's direction (m or rad), any origin
  double plateau = 0.0;        ///< the speed at the top (m/s or rad/s), from the cruise's mean
  bool slowing = false;        ///< plateau -> rest (false: rest -> plateau)
  double start_lo_s = 0.0;     ///< the ramp's start lies in [start_lo_s, start_hi_s]
  double start_hi_s = 0.0;
};

struct RampFit {
  bool ok = false;
  double rate = 0.0;   ///< the acceleration, > 0
  double se = 0.0;     ///< its standard error, from the curvature of the residual sum in the rate
  double rms = 0.0;    ///< residuals' RMS, in the travel's unit
  std::size_t ramps = 0;
};

/// The travel of a ramp that starts at time 0 with rate `rate` to or from
/// `plateau`, at time `u` (before 0: rest for a speed-up, cruise for a slow-down).
double ramp_travel(double u, double rate, double plateau, bool slowing);

/// One rate for every trace (each with its own start and offset), searched
/// around `initial` (within a factor of 4). Not ok with fewer than 2 traces of
/// 4 rows, or when the best rate sits on the search's edge.
RampFit fit_ramp_rate(const std::vector<RampTrace>& traces, double initial);

}  // namespace p3at::verifier::calibration_detail
