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

/// True when r's final components carry time scores (one each) and a
/// positive correlation with its finish time.
bool has_time_scores(const RobotOutcome& r);

/// The robot whose finish time is the branch's completion time and whose
/// final components carry time scores (see above); none when no robot's
/// does, or more than one robot's finish is the completion.
std::optional<std::size_t> time_coupled_robot(const Branch& b);

/// P(t <= T | score z) for P(t <= T) = p_time and correlation rho.
double time_given_score(double p_time, double rho, double z);

/// What the copula needs of a robot's final components: their time scores,
/// weights and the correlation (a copy, so that it outlives the outcome).
struct TimeScores {
  std::vector<double> scores, weights;
  double rho = 0.0;
};
/// r's (r has time scores).
TimeScores time_scores_of(const RobotOutcome& r);

/// P(t <= T | component k) for each component, for P(t <= T) = p_time,
/// rescaled so that over the components they average to p_time exactly (a
/// handful of points stand for the paths' circle: the copula's margin over
/// them is off by a little). The one place both vipars verify's joint and a
/// criterion's use the copula.
std::vector<double> time_given_components(const TimeScores& s, double p_time);

/// A branch's radius probabilities at a list of Rmax, kept apart where the
/// joint with the completion time needs them.
class BranchRadii {
 public:
  BranchRadii(const Branch& b, const mission::Mission& mission, const std::vector<double>& rmax);
  /// P(every robot within rmax[j]) (the radius curve's term).
  double radius(std::size_t j) const { return radius_[j]; }
  /// P(t <= T and every robot within rmax[j]) for every j, for P(t <= T) =
  /// p_time: p_time times radius(j) when no robot is coupled. All Rmax at
  /// once: the conditional times depend on p_time alone.
  std::vector<double> joints(double p_time) const;

 private:
  std::vector<double> radius_;          ///< per Rmax
  std::vector<double> others_;          ///< per Rmax: the uncoupled robots' product
  std::vector<std::vector<double>> within_;  ///< per Rmax, per coupled component: its weight x P(within)
  std::optional<TimeScores> coupled_;        ///< the coupled robot's (time_coupled_robot), if any
};

}  // namespace p3at::verifier::engine
