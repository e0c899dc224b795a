#pragma once
/// Empirical probabilities of a validation campaign: what fraction of the
/// runs met the mission's criteria, on the same quantities and grid as the
/// verifier's prediction (verifier/verify.hpp), each with a 95 % Wilson
/// score interval, so a prediction can be checked against the runs.
///
/// A run that failed (a robot aborted, or the run timed out) is never
/// dropped: its completion time is +inf, so it never meets a time criterion,
/// and its distances are the robots' true distances to their goals where the
/// run ended, so it may still meet a radius criterion.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/team_sim/run_result.hpp"

namespace p3at::team_sim {

/// A proportion observed over runs, with its 95 % Wilson score interval.
struct Estimate {
  std::uint64_t count = 0;  ///< runs for which the event held
  std::uint64_t runs = 0;   ///< runs observed
  double p = 0.0;           ///< count / runs (0 when there are no runs)
  double ci_low = 0.0;
  double ci_high = 1.0;
};
Estimate estimate(std::uint64_t count, std::uint64_t runs);

/// The completion time the time criterion sees: RunResult::time_s for a
/// successful run, +inf for any other.
double completion_time_s(const RunResult& run);
/// The largest true distance to goal over the run's robots (NaN counts as +inf).
double worst_distance_m(const RunResult& run);

struct RobotEmpirical {
  std::string name;
  Estimate radius;                   ///< P(this robot's r <= rmax)
  double dist_mean_m = 0.0;          ///< over every run, failed ones included
  double dist_sd_m = 0.0;            ///< sample standard deviation (0 for one run)
};

/// The campaign's figures at one (tmax, rmax).
struct EmpiricalPoint {
  double tmax_s = 0.0;
  double rmax_m = 0.0;
  std::uint64_t runs = 0;
  std::uint64_t failed_runs = 0;     ///< runs whose outcome is not "success"
  Estimate time;                     ///< P(t <= tmax)
  Estimate radius;                   ///< P(every r_i <= rmax)
  Estimate joint;                    ///< P(t <= tmax and every r_i <= rmax)
  std::vector<RobotEmpirical> robots;           ///< named and ordered as in the first run
  std::optional<double> completion_mean_s;      ///< over the successful runs; none if there are none
  std::optional<double> completion_sd_s;
};
EmpiricalPoint empirical_at(const std::vector<RunResult>& runs, double tmax_s, double rmax_m);

/// The paper's three regions of a (tmax, rmax) cell, by the joint probability:
/// below `low` unsuccessful, at or above `high` successful, else uncertain.
enum class Region { unsuccessful, uncertain, successful };
Region classify(double p_joint, double low, double high);
const char* to_string(Region region);  ///< "unsuccessful", "uncertain", "successful"

struct EmpiricalGrid {
  std::vector<double> tmax;                      ///< axis, as given
  std::vector<double> rmax;                      ///< axis, as given
  std::vector<Estimate> time;                    ///< per tmax
  std::vector<Estimate> radius;                  ///< per rmax
  std::vector<std::vector<Estimate>> joint;      ///< [tmax][rmax]
};
/// Every cell at once: O(runs · log + cells), so a fine grid over a large
/// campaign stays cheap. The axes may be in any order.
EmpiricalGrid empirical_grid(const std::vector<RunResult>& runs, const std::vector<double>& tmax,
                             const std::vector<double>& rmax);

}  // namespace p3at::team_sim
