#pragma once
// The completion time and the final positions of one branch, together
// (issue 13 item 7; docs/verifier.md, "Time and position together").
//
// Within a branch the model carries the completion time as a mixture and
// each robot's final position as a mixture of the last leg's NOISE paths'
// end points. The two are not independent: a path that NOISE pushes toward
// the goal arrives early and runs out closer to it, one pushed aside arrives
// late and ends farther off. Each final component knows how late its paths
// fired (RobotOutcome::final_time_scores, standardised) and how much of the
// finish time's spread that is (time_score_correlation, rho); the time and
// the score are joined by a Gaussian copula:
//
//   P(t <= T | component k) = Phi((Phi^-1(P(t <= T)) - rho z_k) / sqrt(1 - rho^2))
//
// which keeps the time curve as it was (the copula's margin is P(t <= T)
// itself, staircase and all) and moves the mass between components. Only
// the robot whose finish time is the branch's completion time is coupled
// (its finish is the completion, exactly); the other robots' positions stay
// independent of the completion time, as before.

#include <cstddef>
#include <optional>
#include <vector>

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier::engine {

/// The robot whose finish time is the branch's completion time and whose
/// final components carry time scores (see above); none when no robot's
/// does, or more than one robot's finish is the completion.
std::optional<std::size_t> time_coupled_robot(const Branch& b);

/// P(t <= T | score z) for P(t <= T) = p_time and correlation rho.
double time_given_score(double p_time, double rho, double z);

/// A branch's radius probabilities at a list of Rmax, kept apart where the
/// joint with the completion time needs them.
class BranchRadii {
 public:
  BranchRadii(const Branch& b, const mission::Mission& mission, const std::vector<double>& rmax);
  /// P(every robot within rmax[j]) (the radius curve's term).
  double radius(std::size_t j) const { return radius_[j]; }
  /// P(t <= T and every robot within rmax[j]), for P(t <= T) = p_time:
  /// p_time times radius(j) when no robot is coupled.
  double joint(double p_time, std::size_t j) const;

 private:
  std::vector<double> radius_;          ///< per Rmax
  std::vector<double> others_;          ///< per Rmax: the uncoupled robots' product
  std::vector<std::vector<double>> within_;  ///< per Rmax, per coupled component: its weight x P(within)
  std::vector<double> scores_;          ///< per coupled component
  std::vector<double> weights_;         ///< per coupled component
  double rho_ = 0.0;
  bool coupled_ = false;
};

}  // namespace p3at::verifier::engine
