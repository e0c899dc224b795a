#include "p3at/verifier/verify.hpp"

#include <algorithm>
#include <cmath>

#include "engine/sequencer.hpp"
#include "engine/time_position.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/verifier/criteria.hpp"

namespace p3at::verifier {
namespace {

Status check_models(const mission::Mission& mission, const Models& models) {
  for (const mission::RobotSpec& r : mission.robots) {
    if (models.find_robot(r.name) == nullptr) {
      return make_error(Error::Code::invalid_argument,
                        "the models file " + (models.source.empty() ? std::string("given") : "'" + models.source + "'") +
                            " has no model for mission robot '" + r.name + "' (add a `robots:` entry named '" + r.name +
                            "', e.g. with `vipars calibrate`)");
    }
  }
  return {};
}

struct Point {
  double time = 0.0, radius = 0.0, joint = 0.0;
};

/// E|X - goal| for one Gaussian. Far from the goal (the usual case: at least
/// 3 standard deviations) the second-order expansion of the distance,
/// |d| + (tr S - u'Su) / (2|d|) with u = d/|d|, is exact to far below a
/// millimetre and costs nothing; near the goal the integral of P(|X - g| > r)
/// over r (Simpson, 32 intervals up to 8 standard deviations past the mean).
double expected_distance(const Gaussian2& x, const Eigen::Vector2d& goal) {
  const Eigen::Vector2d d = x.mean - goal;
  const double r = d.norm();
  const double trace = std::max(0.0, x.cov.trace());
  const double sd_max = std::sqrt(trace);  // >= the largest axis's sd
  if (r > 3.0 * sd_max && r > 0.0) {
    const Eigen::Vector2d u = d / r;
    return r + std::max(0.0, trace - u.dot(x.cov * u)) / (2.0 * r);
  }
  const double high = r + 8.0 * sd_max + 1e-6;
  constexpr int kIntervals = 32;  // even, for Simpson
  const double h = high / kIntervals;
  const auto beyond = [&](double radius) { return 1.0 - probability_within(x, goal, radius); };
  double sum = beyond(0.0) + beyond(high);
  for (int k = 1; k < kIntervals; ++k) sum += (k % 2 == 1 ? 4.0 : 2.0) * beyond(k * h);
  return sum * h / 3.0;
}

/// The average of f over robot i's true final position: each branch's final
/// Gaussian, or its mixture when it has final_components, weighted by the
/// branches' weights. Runs at every gate decision, so it stays cheap.
template <typename F>
double final_position_average(const SystemOutcome& o, std::size_t i, const F& f) {
  double w = 0.0, sum = 0.0;
  for (const Branch& b : o.branches) {
    const RobotOutcome& r = b.robots[i];
    double e = 0.0;
    if (r.final_components.empty()) {
      e = f(r.final_position);
    } else {
      for (std::size_t k = 0; k < r.final_components.size(); ++k) e += component_weight(r, k) * f(r.final_components[k]);
    }
    sum += b.weight * e;
    w += b.weight;
  }
  return w > 0.0 ? sum / w : 0.0;
}

/// E|p - goal| of robot i's true final position: the quantity `vipars
/// validate` reports as dist_mean_m, so the two compare directly.
double expected_distance(const SystemOutcome& o, std::size_t i, const Eigen::Vector2d& goal) {
  return final_position_average(o, i, [&goal](const Gaussian2& x) { return expected_distance(x, goal); });
}

/// E|p - goal|^2 over the same mixture, exact (|mean - goal|^2 + trace(cov)
/// per Gaussian): with expected_distance, the spread of the distance itself,
/// which `vipars validate` reports as dist_sd_m. A position spread across the
/// line to the goal barely moves the distance; one along it moves it fully.
double expected_squared_distance(const SystemOutcome& o, std::size_t i, const Eigen::Vector2d& goal) {
  return final_position_average(o, i, [&goal](const Gaussian2& x) {
    return (x.mean - goal).squaredNorm() + std::max(0.0, x.cov.trace());
  });
}

/// The control cycle every robot shares (0 when they differ). Every event of
/// the mission happens on a cycle tick (the executive checks its triggers once
/// per cycle, message delays are seen in whole cycles), so the completion time
/// is a whole number of cycles from launch.
double shared_cycle_s(const Models& models) {
  double c = 0.0;
  for (const RobotModel& m : models.robots) {
    if (c == 0.0) c = m.kinematics.cycle_s;
    if (m.kinematics.cycle_s != c) return 0.0;
  }
  return c > 0.0 ? c : 0.0;
}

/// P(t <= Tmax) for a completion time on the cycle lattice, from the
/// continuous mixture that carries it (the durations' components have
/// widths, issue 13 item 10): the mass of the lattice points at or below Tmax
/// is the mixture's mass below the midpoint to the next one (a continuity
/// correction). Without it a short mission's curve passes between the steps
/// of the true staircase, up to half a cycle's mass off.
/// A completion time the model could not define (a non-finite moment, which is
/// a verifier bug: see undefined_completion) counts as never done: failure,
/// never a GO.
double time_cdf(const Mixture1& t, double tmax, double cycle_s) {
  const double p = cycle_s > 0.0 ? t.cdf(cycle_s * std::floor(tmax / cycle_s + 1e-9) + 0.5 * cycle_s) : t.cdf(tmax);
  return std::isfinite(p) ? p : 0.0;
}

/// The probability mass of branches whose completion time has a non-finite
/// weight, mean or variance.
double undefined_completion(const SystemOutcome& o) {
  double mass = 0.0;
  for (const Branch& b : o.branches) {
    for (const Component1& c : b.completion_time_s.components) {
      if (!std::isfinite(c.weight) || !std::isfinite(c.mean) || !std::isfinite(c.var)) {
        mass += b.weight;
        break;
      }
    }
  }
  return mass;
}

/// P(t <= Tmax): needs only the completion times, no disk integrals.
double time_probability(const SystemOutcome& o, double tmax, double cycle_s) {
  double p = 0.0;
  for (const Branch& b : o.branches) p += b.weight * time_cdf(b.completion_time_s, tmax, cycle_s);
  return p;
}

Point probabilities(const SystemOutcome& o, const mission::Mission& mission, double tmax, double rmax, double cycle_s) {
  Point p;
  for (const Branch& b : o.branches) {
    const double pt = time_cdf(b.completion_time_s, tmax, cycle_s);
    const engine::BranchRadii radii(b, mission, {rmax});
    p.time += b.weight * pt;
    p.radius += b.weight * radii.radius(0);
    p.joint += b.weight * radii.joints(pt)[0];  // time and position together (engine/time_position.hpp)
  }
  return p;
}

/// Mixture over branches of a per-branch mixture, for summaries.
void moments(const std::vector<std::pair<double, const Mixture1*>>& parts, double& mean, double& sd) {
  double w = 0.0, m = 0.0, s2 = 0.0;
  for (const auto& [weight, x] : parts) {
    w += weight;
    m += weight * x->mean();
  }
  if (!(w > 0.0)) {
    mean = sd = 0.0;
    return;
  }
  m /= w;
  for (const auto& [weight, x] : parts) {
    const double d = x->mean() - m;
    s2 += weight * (x->variance() + d * d);
  }
  mean = m;
  sd = std::sqrt(std::max(0.0, s2 / w));
}

Region classify(double p, const VerifyOptions& options) {
  if (p < options.region_low) return Region::unsuccessful;
  if (p >= options.region_high) return Region::successful;
  return Region::uncertain;
}

std::string fixed(double v, int decimals) { return format_fixed(v, decimals); }

// The criterion point (the mission's, overridden by the options), checked.
Result<VerifyResult> criteria_point(const mission::Mission& mission, const VerifyOptions& options) {
  VerifyResult r;
  r.tmax_s = options.tmax_s.value_or(mission.criteria.tmax_s);
  r.rmax_m = options.rmax_m.value_or(mission.criteria.rmax_m);
  r.threshold = options.threshold.value_or(mission.criteria.threshold);
  if (!(r.tmax_s > 0.0) || !(r.rmax_m > 0.0)) {
    return make_error(Error::Code::invalid_argument, "Tmax and Rmax must be positive (got tmax " + fixed(r.tmax_s, 3) +
                                                         " s, rmax " + fixed(r.rmax_m, 3) + " m)");
  }
  if (!(r.threshold >= 0.0 && r.threshold <= 1.0)) {
    return make_error(Error::Code::invalid_argument, "threshold must be in [0, 1], got " + fixed(r.threshold, 4));
  }
  return r;
}

}  // namespace

const char* to_string(Decision d) {
  switch (d) {
    case Decision::go: return "go";
    case Decision::no_go: return "no-go";
    case Decision::cannot_evaluate: return "cannot-evaluate";
  }
  return "?";
}

void locate_in_mission_file(VerifyResult& result, std::string_view mission_yaml, const std::string& mission_file) {
  const MissionLocator locator(mission_yaml, mission_file);
  locate_approximations(result.approximations, locator);
  for (BlockedRobot& b : result.blocked) b.where = locator.where(b.robot, MissionElement::state, b.state);
}

Result<SystemOutcome> evaluate_system(const mission::Mission& mission, const Models& models, const TeamSnapshot* from) {
  if (const Status st = check_models(mission, models); !st) return st.error();
  if (from != nullptr && from->robots.size() != mission.robots.size()) {
    return make_error(Error::Code::invalid_argument, "snapshot has " + std::to_string(from->robots.size()) +
                                                         " robots, the mission " + std::to_string(mission.robots.size()));
  }
  if (from != nullptr) {
    for (std::size_t i = 0; i < from->robots.size(); ++i) {
      if (from->robots[i].state >= mission.robots[i].states.size()) {
        return make_error(Error::Code::invalid_argument, "snapshot: robot '" + mission.robots[i].name + "' state index " +
                                                             std::to_string(from->robots[i].state) + " out of range");
      }
    }
  }
  return engine::run_sequence(mission, models, from);
}

Result<VerifyResult> verify(const mission::Mission& mission, const Models& models, const VerifyOptions& options,
                            const std::vector<std::string>& criteria_files, const TeamSnapshot* from) {
  // Bad criteria are refused before the expensive evaluation.
  if (Result<VerifyResult> checked = criteria_point(mission, options); !checked) return checked.error();
  Result<SystemOutcome> evaluated = evaluate_system(mission, models, from);
  if (!evaluated) return evaluated.error();
  return verify_outcome(mission, models, *evaluated, options, criteria_files);
}

Result<VerifyResult> verify_outcome(const mission::Mission& mission, const Models& models, const SystemOutcome& o,
                                    const VerifyOptions& options, const std::vector<std::string>& criteria_files) {
  Result<VerifyResult> checked = criteria_point(mission, options);
  if (!checked) return checked.error();
  VerifyResult r = std::move(*checked);

  const double cycle_s = shared_cycle_s(models);
  const Point p = probabilities(o, mission, r.tmax_s, r.rmax_m, cycle_s);
  r.p_time = std::clamp(p.time, 0.0, 1.0);
  r.p_radius = std::clamp(p.radius, 0.0, 1.0);
  r.p_joint = std::clamp(p.joint, 0.0, 1.0);
  r.pruned_mass = o.pruned_mass;
  r.budget_merged_mass = o.budget_merged_mass;
  r.blocked_mass = o.blocked_mass;
  r.loop_cutoff_mass = o.loop_cutoff_mass;
  r.work_cutoff_mass = o.work_cutoff_mass;
  r.work_cycles = o.work_cycles;
  r.branches = o.branches.size();
  r.subsystems = o.subsystems;

  for (const BlockedRecord& b : o.blocked) {
    if (b.mass < 1e-9) continue;
    BlockedRobot br;
    br.robot = b.robot;
    br.name = mission.robots[b.robot].name;
    br.state = b.state;
    br.state_name = mission.robots[b.robot].states[b.state].name;
    br.x_m = b.x_m;
    br.y_m = b.y_m;
    br.why = b.why;
    br.probability = std::min(1.0, b.mass);
    r.blocked.push_back(std::move(br));
  }
  r.approximations = detect_approximations(mission, models, o);
  r.evaluable = all_vouched(r.approximations);

  std::vector<std::pair<double, const Mixture1*>> completion;
  for (const Branch& b : o.branches) completion.emplace_back(b.weight, &b.completion_time_s);
  moments(completion, r.completion_mean_s, r.completion_sd_s);
  for (std::size_t i = 0; i < mission.robots.size(); ++i) {
    RobotPrediction rp;
    rp.name = mission.robots[i].name;
    std::vector<std::pair<double, const Mixture1*>> finish;
    double w = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    const Eigen::Vector2d goal(mission.robots[i].goal.x_m, mission.robots[i].goal.y_m);
    for (const Branch& b : o.branches) {
      finish.emplace_back(b.weight, &b.robots[i].finish_time_s);
      w += b.weight;
      mean += b.weight * b.robots[i].final_position.mean;
      rp.p_radius += b.weight * final_within(b.robots[i], goal, r.rmax_m);
    }
    moments(finish, rp.finish_mean_s, rp.finish_sd_s);
    if (w > 0.0) {
      mean /= w;
      for (const Branch& b : o.branches) {
        const Eigen::Vector2d d = b.robots[i].final_position.mean - mean;
        cov += (b.weight / w) * (b.robots[i].final_position.cov + d * d.transpose());
      }
    }
    rp.final_x_m = mean.x();
    rp.final_y_m = mean.y();
    rp.final_sd_m = std::sqrt(std::max(0.0, cov.trace() / 2.0));
    rp.dist_mean_m = expected_distance(o, i, goal);
    rp.dist_sd_m = std::sqrt(std::max(0.0, expected_squared_distance(o, i, goal) - rp.dist_mean_m * rp.dist_mean_m));
    rp.finishes = w > 0.0;
    for (const BlockedRobot& b : r.blocked) {
      if (b.robot == i) rp.p_blocked += b.probability;
    }
    rp.p_blocked = std::min(1.0, rp.p_blocked);
    r.robots.push_back(rp);
  }

  if (!options.tmax_grid.empty() || !options.rmax_grid.empty()) {
    Grid g;
    g.tmax = options.tmax_grid.empty() ? std::vector<double>{r.tmax_s} : options.tmax_grid;
    g.rmax = options.rmax_grid.empty() ? std::vector<double>{r.rmax_m} : options.rmax_grid;
    // Sums over branches can round a hair past 1 (weights are products of
    // split probabilities): probabilities are reported within [0, 1].
    const auto unit = [](double q) { return std::clamp(q, 0.0, 1.0); };
    for (const double t : g.tmax) g.p_time.push_back(unit(time_probability(o, t, cycle_s)));
    // Per-branch radius probabilities are shared by every Tmax: compute them once.
    std::vector<engine::BranchRadii> radius;
    for (const Branch& b : o.branches) radius.emplace_back(b, mission, g.rmax);
    for (std::size_t j = 0; j < g.rmax.size(); ++j) {
      double pr = 0.0;
      for (std::size_t b = 0; b < o.branches.size(); ++b) pr += o.branches[b].weight * radius[b].radius(j);
      g.p_radius.push_back(unit(pr));
    }
    for (const double t : g.tmax) {
      std::vector<double> row(g.rmax.size(), 0.0);
      std::vector<Region> regions;
      for (std::size_t b = 0; b < o.branches.size(); ++b) {
        const std::vector<double> joint = radius[b].joints(time_cdf(o.branches[b].completion_time_s, t, cycle_s));
        for (std::size_t j = 0; j < g.rmax.size(); ++j) row[j] += o.branches[b].weight * joint[j];
      }
      for (double& v : row) v = unit(v);
      for (const double v : row) regions.push_back(classify(v, options));
      g.p_joint.push_back(std::move(row));
      g.region.push_back(std::move(regions));
    }
    r.grid = std::move(g);
  }

  // Extra criteria (PARS networks with constraints): parsed and checked
  // against the same final distribution; a file that cannot be read or does
  // not match the system's structure is an error, never a silent 0.
  for (const std::string& file : criteria_files) {
    Criterion criterion;
    try {
      criterion = load_criterion_file(file);
    } catch (const CriterionError& e) {
      return make_error(Error::Code::invalid_argument, e.what());
    }
    // A separation is decided a step stricter: the distance two robots at
    // the team's top speed close in one cycle (twice the radius floor).
    Result<CriterionVerdict> verdict =
        evaluate_criterion(criterion, mission, o, r.threshold, 2.0 * decision_floors(mission, models).radius_m);
    if (!verdict) return verdict.error();  // the message already names the file
    r.criteria.push_back(*verdict);
  }

  // Kinds whose error is a small shift of the curves: decide at a stricter point.
  const bool widen = std::any_of(r.approximations.begin(), r.approximations.end(), [](const Approximation& a) {
    return approximation_row(a.kind).treatment == Treatment::widen;
  });
  r.floors = decision_floors(mission, models);
  const DecisionPoint at = decision_point(r.tmax_s, r.rmax_m, widen, r.floors);
  r.widened = widen;
  r.decided_tmax_s = at.tmax_s;
  r.decided_rmax_m = at.rmax_m;
  r.p_joint_decided = probabilities(o, mission, at.tmax_s, at.rmax_m, cycle_s).joint;
  const double decided = r.p_joint_decided;
  r.go = decided >= r.threshold;
  for (const CriterionVerdict& c : r.criteria) {
    if (!c.holds) {
      r.go = false;
      r.failed.push_back("criterion " + c.name + ": P = " + fixed(c.probability, 3) + " < required " +
                         fixed(c.required, 3) + (c.explanation.empty() ? std::string() : " (" + c.explanation + ")"));
    }
  }
  if (r.p_joint >= r.threshold && decided < r.threshold) {
    r.failed.push_back("P(t <= " + fixed(at.tmax_s, 2) + " s and every r_i <= " + fixed(at.rmax_m, 3) + " m) = " +
                       fixed(decided, 3) + " < threshold " + fixed(r.threshold, 3) +
                       " (decided there, not at Tmax and Rmax: " + decision_margin_text(r) + ", docs/verifier.md)");
  }
  // Never a GO on numbers the model could not define (counted as failure above).
  if (const double undefined = undefined_completion(o); undefined > 0.0) {
    r.go = false;
    r.failed.push_back("the model could not define the completion time of " + fixed(undefined, 4) +
                       " of the probability mass (a non-finite variance: a verifier fault, please report the "
                       "mission); that mass is counted as failure and the mission is refused");
  }
  if (r.p_joint < r.threshold) {
    r.failed.push_back("P(t <= " + fixed(r.tmax_s, 1) + " s and every r_i <= " + fixed(r.rmax_m, 2) + " m) = " +
                       fixed(r.p_joint, 3) + " < threshold " + fixed(r.threshold, 3) + " (P(t <= Tmax) = " +
                       fixed(r.p_time, 3) + ", P(r <= Rmax) = " + fixed(r.p_radius, 3) + ")");
  }
  return r;
}

DecisionFloors decision_floors(const mission::Mission& mission, const Models& models) {
  DecisionFloors f;
  for (const mission::RobotSpec& robot : mission.robots) {
    const RobotModel* model = models.find_robot(robot.name);
    const double cycle_s = model != nullptr ? model->kinematics.cycle_s : Kinematics{}.cycle_s;
    f.time_s = std::max(f.time_s, cycle_s);
    f.radius_m = std::max(f.radius_m, robot.max_speed_mps * cycle_s);
  }
  return f;
}

std::string decision_margin_text(const VerifyResult& r) {
  return "the gate's margin: 1 % stricter, at least one cycle (" + fixed(r.floors.time_s, 2) + " s) and one step (" +
         fixed(r.floors.radius_m, 3) + " m)" +
         (r.widened ? std::string(", and an approximation that shifts the curves") : std::string());
}

DecisionPoint decision_point(double tmax_s, double rmax_m, bool widen, const DecisionFloors& floors) {
  DecisionPoint d{std::min(tmax_s * (1.0 - kDecisionMargin), tmax_s - floors.time_s),
                  std::max(0.0, std::min(rmax_m * (1.0 - kDecisionMargin), rmax_m - floors.radius_m))};
  if (widen) {
    d.tmax_s = std::min(d.tmax_s, tmax_s - kWidenTime_s);
    d.rmax_m = std::min(d.rmax_m, std::max(0.0, rmax_m - kWidenRadius_m));
  }
  return d;
}

}  // namespace p3at::verifier
