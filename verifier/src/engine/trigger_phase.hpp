#pragma once
/// Where within its last cycle a trigger fires (issue 13 item 5). The
/// executive checks AtGoal and HasTurned once per cycle, so a real run whose
/// threshold crossing falls at continuous time T (in cycles from the state's
/// entry) fires at the first check after it, ceil(T). Over runs, T varies:
/// where it varies by a cycle or more (NOISE's direction changes the path
/// within one quadrature node's arc), the firing is on average half a cycle
/// after the crossing; where it hardly varies (no NOISE, a leg started from
/// rest at a cycle boundary, as after a Notified), the firing is the one
/// deterministic check after T. A deterministic path has one T; with the
/// spread of T over its node's arc, the expected gap E[ceil(T) - T] is
/// between the two.

#include <cstdint>
#include <vector>

namespace p3at::verifier::engine {

/// The gap G = ceil(X) - X between a crossing at X ~ N(t, sd^2) and the
/// check that fires, summed exactly over the cells (k - 1, k] within 8 sd.
struct CheckGap {
  /// E[G], in (0, 1]: 1 - frac(t) (1 at an integer) for sd = 0, tending to
  /// 1/2 as sd grows.
  double mean = 0.5;
  /// Var[G]: 0 for sd = 0 (one deterministic check), tending to 1/12 (a
  /// uniform gap) as sd grows, and up to 1/4 in between when the crossing
  /// straddles a check (the firing is at one check or the next). Times the
  /// last cycle's step, it is how far along that step the firing pose spreads.
  double var = 1.0 / 12.0;
};
CheckGap check_gap(double t, double sd);

/// The checks a crossing at X ~ N(t, sd^2) fires at: check n (cycles from
/// the entry) when X falls in (n - 1, n], with P = Phi((n - t) / sd) -
/// Phi((n - 1 - t) / sd), over the checks within 8 sd (from check 1; shares
/// below 1e-12 left out). For sd = 0 the one check ceil(t) (t itself on a
/// check) with share 1.
struct CheckShare {
  std::int64_t check = 0;
  double share = 0.0;
};
std::vector<CheckShare> check_shares(double t, double sd);

/// check_gap(t, sd).mean and .var.
double expected_check_gap(double t, double sd);
double check_gap_variance(double t, double sd);

}  // namespace p3at::verifier::engine
