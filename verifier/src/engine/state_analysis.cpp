#include "engine/state_analysis.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>
#include <variant>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "engine/error_strata.hpp"
#include "engine/held_duration.hpp"
#include "engine/interruption.hpp"
#include "engine/next_turn.hpp"
#include "engine/noise_segments.hpp"
#include "engine/stuck_profile.hpp"
#include "engine/trajectory_pace.hpp"
#include "engine/trigger_phase.hpp"

namespace p3at::verifier::engine {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
// Cycles a state may take, beyond its nominal length, before its path is
// declared stuck: generous, so a slow but moving robot is never called stuck.
constexpr std::size_t kMinCycleCap = 3000;
// A group of paths that made other whole turns than the rest and carries
// less than this share of the mass is slabbed with the rest (its own points
// would be weight too small to matter).
constexpr double kMinTurnGroupShare = 1e-3;

/// The self-timed triggers of a still robot's state: the first that holds at
/// pose q, in file order (the executive's order), or nothing.
std::optional<std::size_t> fired_exit(const mission::RobotSpec& robot, std::size_t state, const BaseState& q,
                                      double turned_rad) {
  for (const std::size_t t : robot.states[state].outgoing) {
    const mission::TriggerParams& trigger = robot.transitions[t].trigger;
    if (const auto* g = std::get_if<mission::AtGoalParams>(&trigger)) {
      if (std::hypot(g->goal.x_m - q.x_m, g->goal.y_m - q.y_m) <= g->radius_m) return t;
    } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
      if (turned_rad >= (h->angle_deg - h->offset_deg) * kDegToRad) return t;
    }
  }
  return std::nullopt;
}

bool has_trigger_kind(const mission::RobotSpec& robot, std::size_t state, mission::TriggerKind kind) {
  return std::any_of(robot.states[state].outgoing.begin(), robot.states[state].outgoing.end(),
                     [&](std::size_t t) { return robot.transitions[t].kind() == kind; });
}

/// The cycle cap for a state: ten times its nominal length, at least kMinCycleCap.
std::size_t cycle_cap(const StateContext& ctx, std::size_t state, const BaseState& start) {
  const mission::RobotSpec& robot = *ctx.robot;
  double nominal_s = 0.0;
  if (const auto* go = std::get_if<mission::GoToGuardedParams>(&robot.states[state].behavior)) {
    nominal_s = std::hypot(go->goal.x_m - start.x_m, go->goal.y_m - start.y_m) / std::max(robot.max_speed_mps, 1e-3);
  }
  return std::max(kMinCycleCap, static_cast<std::size_t>(10.0 * nominal_s / ctx.model->kinematics.cycle_s));
}

/// The error at the end of a motion state, carried forward from the MEAN
/// odometric end pose. Much of the error is a function of the odometric pose
/// itself (a rotation-scale error is (k - 1) times the net odometric turn; a
/// distance-scale error grows with the odometric displacement), and the next
/// state re-steers from wherever odometry says the robot is, which undoes it
/// (a path that turned 5 degrees more turns 5 degrees less next). So the part
/// of the paths' error spread that is explained by their differing end poses
/// is not a spread the robot keeps: regress the paths' error means on their
/// end poses (weighted least squares) and carry the residual spread, plus
/// each path's own (within-path) covariance.
///
/// Except for what re-steering never undoes: paths that turned around one way
/// or the other (`turns`: whole turns between a path's continuous heading and
/// the first path's) face the same way, but with heading errors of opposite
/// sign that the rest of the mission turns into lateral errors of opposite
/// sign. The regression is fitted within each such group (one slope, one
/// intercept per group), so the groups' difference stays in the residual.
/// The residuals are also returned as the components of `paths`
/// (engine/error_mixture), reduced to kMaxErrorComponents: one Gaussian would
/// put most of a two-sided error near zero. Measured on generated gen_1166
/// (a U-turn at the start of an 8 m leg, rot_scale 1.02) cut after its 7
/// states (`vipars validate`, 400 runs: the robot ends 0.482 m from its goal
/// on average): 0.276 m predicted with one Gaussian and the regression over
/// all paths (the U-turn's two groups ended on the two sides of the arc, so
/// the end positions "explained" their errors), 0.477 m carrying everything.
ErrorState error_given_end(const std::vector<FinishedPath>& done, const std::vector<long>& turns,
                           ErrorMixture* paths = nullptr, std::vector<Eigen::Vector3d>* explained = nullptr) {
  ErrorState out;
  if (explained != nullptr) explained->assign(done.size(), Eigen::Vector3d::Zero());
  double total = 0.0;
  for (const FinishedPath& p : done) total += p.walker.weight;
  if (done.empty() || !(total > 0.0)) return out;
  const auto pose = [](const FinishedPath& p) { return Eigen::Vector3d(p.walker.q.x_m, p.walker.q.y_m, p.walker.q.theta_rad); };
  // Overall and per-group weighted means.
  std::map<long, double> group_w;
  std::map<long, Eigen::Vector3d> group_q, group_e;
  Eigen::Vector3d q_mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < done.size(); ++i) {
    const FinishedPath& p = done[i];
    const double f = p.walker.weight / total;
    out.mean += f * p.walker.error.mean;
    q_mean += f * pose(p);
    const long g = turns[i];
    group_w[g] += f;
    group_q.try_emplace(g, Eigen::Vector3d::Zero()).first->second += f * pose(p);
    group_e.try_emplace(g, Eigen::Vector3d::Zero()).first->second += f * p.walker.error.mean;
  }
  for (auto& [g, w] : group_w) {
    if (w > 0.0) {
      group_q[g] /= w;
      group_e[g] /= w;
    }
  }
  // Centred (within its group), weight-scaled regressors and responses; a
  // small ridge keeps a degenerate spread (all paths alike, or a straight
  // line of end points) well posed.
  const auto rows = static_cast<Eigen::Index>(done.size());
  Eigen::MatrixXd x(rows, 3), y(rows, 3);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const FinishedPath& p = done[static_cast<std::size_t>(i)];
    const long g = turns[static_cast<std::size_t>(i)];
    const double s = std::sqrt(p.walker.weight / total);
    x.row(i) = s * (pose(p) - group_q[g]).transpose();
    y.row(i) = s * (p.walker.error.mean - group_e[g]).transpose();
  }
  const Eigen::Matrix3d xtx = x.transpose() * x + 1e-9 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d b = xtx.ldlt().solve(x.transpose() * y);  // y ≈ x b
  for (Eigen::Index i = 0; i < rows; ++i) {
    const FinishedPath& p = done[static_cast<std::size_t>(i)];
    const long g = turns[static_cast<std::size_t>(i)];
    // Within the group, what the pose does not explain; plus the group's own
    // offset, less what its mean pose explains.
    const Eigen::Vector3d r = (p.walker.error.mean - group_e[g]) - b.transpose() * (pose(p) - group_q[g]) +
                              (group_e[g] - out.mean) - b.transpose() * (group_q[g] - q_mean);
    const double f = p.walker.weight / total;
    out.cov += f * (p.walker.error.cov + r * r.transpose());
    // What the path's end pose explains (its error is the mean plus this plus r).
    if (explained != nullptr) (*explained)[static_cast<std::size_t>(i)] = b.transpose() * (pose(p) - q_mean);
    if (paths != nullptr && f > 0.0) paths->push_back({f, r, Eigen::Matrix3d::Zero()});
  }
  if (paths != nullptr) reduce(*paths, kMaxErrorComponents);
  return out;
}

/// The duration of one exit when NOISE redrew within the state: the cycles
/// at which the segment quadrature's paths fired, with their weights. Those
/// paths are a few hundred representatives of a continuum (each stands for
/// the neighbourhood of states its cluster merged), so each gets a kernel of
/// Silverman's width (from the smaller of the sd and the interquartile
/// range, so a long tail does not blur the core), the points pulled toward
/// their mean so the variance stays theirs. Without the kernel the curve
/// comes in lumps, one per burst of paths firing together.
Mixture1 redrawn_duration(const std::vector<double>& values, const std::vector<double>& weights,
                          std::size_t max_components) {
  double total = 0.0, total2 = 0.0, mean = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    total += weights[i];
    total2 += weights[i] * weights[i];
    mean += weights[i] * values[i];
  }
  mean /= total;
  double var = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) var += weights[i] / total * (values[i] - mean) * (values[i] - mean);
  // Weighted quartiles.
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  auto quantile = [&](double p) {
    double cum = 0.0;
    for (const std::size_t i : order) {
      cum += weights[i] / total;
      if (cum >= p) return values[i];
    }
    return values[order.back()];
  };
  const double iqr = quantile(0.75) - quantile(0.25);
  const double n_eff = total * total / total2;
  const double scale = std::min(std::sqrt(var), iqr > 0.0 ? iqr / 1.349 : std::sqrt(var));
  const double h = 0.9 * scale * std::pow(n_eff, -0.2);
  const double kernel = std::min(h * h, 0.5 * var);
  const double pull = var > 0.0 ? std::sqrt((var - kernel) / var) : 1.0;
  Mixture1 m;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (weights[i] > 0.0) m.components.push_back({weights[i] / total, mean + pull * (values[i] - mean), kernel});
  }
  reduce(m, max_components);
  return m;
}

/// The same, but a kernel never spreads mass across a redraw: paths held
/// off their goal by a NOISE direction escape after the next redraw, so the
/// duration comes in lumps one draw apart (generated gen_1042's 8.6 m leg,
/// persistence 800: 41 % of runs at 54-63 s, 53 % at 80-82 s, 4 % near
/// 160 s; one kernel over them all made it one smooth 79 +- 31 s). When the
/// draws are long against the lumps (persistence > 4 x the firings' spread
/// within a draw) and not negligible against the whole spread (> a quarter of
/// its sd), each draw's firings get their own kernel; shorter draws blur
/// together anyway. The test was once against the whole's kernel, which the
/// lumps' spacing itself widens: generated gen_7719's first leg (persistence
/// 48 s, lumps 1-2 s wide at 34, 52, 100, 148 s... in 2,000 runs) had a
/// whole kernel of 12 s, just over a quarter of the draw, and came out one
/// smooth curve 0.26 below the runs at 53 s.
Mixture1 redrawn_duration_by_draw(const std::vector<double>& values, const std::vector<double>& weights,
                                  const std::vector<std::size_t>& segments, double persistence_s,
                                  std::size_t max_components) {
  const Mixture1 whole = redrawn_duration(values, weights, max_components);
  std::map<std::size_t, std::pair<std::vector<double>, std::vector<double>>> by_draw;
  double total = 0.0, sum = 0.0, sum2 = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    by_draw[segments[i]].first.push_back(values[i]);
    by_draw[segments[i]].second.push_back(weights[i]);
    total += weights[i];
    sum += weights[i] * values[i];
    sum2 += weights[i] * values[i] * values[i];
  }
  if (by_draw.size() < 2 || !(total > 0.0)) return whole;
  // The pooled spread within the draws, and the whole's.
  double within = 0.0;
  for (const auto& [segment, group] : by_draw) {
    (void)segment;
    double mass = 0.0, gsum = 0.0;
    for (std::size_t j = 0; j < group.first.size(); ++j) {
      mass += group.second[j];
      gsum += group.second[j] * group.first[j];
    }
    if (!(mass > 0.0)) continue;
    const double gmean = gsum / mass;
    for (std::size_t j = 0; j < group.first.size(); ++j) within += group.second[j] * (group.first[j] - gmean) * (group.first[j] - gmean);
  }
  const double whole_sd = std::sqrt(std::max(0.0, sum2 / total - (sum / total) * (sum / total)));
  const bool lumps = persistence_s > 4.0 * std::sqrt(within / total) && persistence_s > 0.25 * whole_sd;
  if (!lumps) return whole;
  Mixture1 out;
  for (const auto& [segment, group] : by_draw) {
    (void)segment;
    double mass = 0.0;
    for (const double w : group.second) mass += w;
    if (!(mass > 0.0)) continue;
    const Mixture1 part = redrawn_duration(group.first, group.second, max_components);
    for (const Component1& c : part.components) out.components.push_back({c.weight * mass / total, c.mean, c.var});
  }
  out.normalise();
  reduce(out, max_components);
  return out;
}

/// `directions` equal-weight points standing for the finished paths' end
/// positions (relative to `mean`): the paths sorted by their bearing from the
/// goal (their ends lie on the AtGoal circle), cut into slabs of equal
/// probability, each slab's weighted mean. `moved` (empty, or one per path)
/// is added to each path's end first: where each comes to rest.
std::vector<Eigen::Vector2d> equal_weight_ends(const std::vector<FinishedPath>& done, const Eigen::Vector2d& goal,
                                               const Eigen::Vector2d& mean, const Eigen::Vector2d& error_mean,
                                               std::size_t directions, const std::vector<Eigen::Vector2d>& moved = {}) {
  std::vector<Eigen::Vector2d> out;
  double total = 0.0;
  for (const FinishedPath& p : done) total += p.walker.weight;
  if (done.empty() || !(total > 0.0)) return out;
  const auto end_of = [&](std::size_t i) {
    // The true end (odometric end plus the error's deviation).
    const Eigen::Vector2d at =
        Eigen::Vector2d(done[i].walker.q.x_m, done[i].walker.q.y_m) + done[i].walker.error.mean.head<2>() - error_mean;
    return moved.empty() ? at : Eigen::Vector2d(at + moved[i]);
  };
  const Eigen::Vector2d towards = mean - goal;
  const double centre = std::atan2(towards.y(), towards.x());
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < done.size(); ++i) {
    // Sorted by the true end's bearing: paths whose errors differ (a turn
    // made one way or the other) end on different sides, and must not be
    // averaged into one slab.
    const Eigen::Vector2d at = end_of(i);
    const double a = std::atan2(at.y() - goal.y(), at.x() - goal.x()) - centre;
    order.emplace_back(std::remainder(a, 2.0 * kPi), i);
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  // Each path covers [c0, c1) of the cumulative probability; slab k is
  // [k, k + 1) x total / directions; a path's share of a slab is the overlap.
  const double slab = total / static_cast<double>(directions);
  std::vector<Eigen::Vector2d> sums(directions, Eigen::Vector2d::Zero());
  std::vector<double> masses(directions, 0.0);
  double c0 = 0.0;
  for (const auto& [angle, i] : order) {
    (void)angle;
    const FinishedPath& p = done[i];
    const double c1 = c0 + p.walker.weight;
    const Eigen::Vector2d at = end_of(i);
    for (std::size_t k = 0; k < directions; ++k) {
      const double overlap = std::min(c1, static_cast<double>(k + 1) * slab) - std::max(c0, static_cast<double>(k) * slab);
      if (overlap > 0.0) {
        sums[k] += overlap * at;
        masses[k] += overlap;
      }
    }
    c0 = c1;
  }
  for (std::size_t k = 0; k < directions; ++k) out.push_back(masses[k] > 0.0 ? Eigen::Vector2d(sums[k] / masses[k] - mean) : Eigen::Vector2d::Zero());
  return out;
}

/// Whole turns between each path's continuous end heading and the first
/// path's: paths that turned around one way or the other face the same way,
/// a whole turn apart as numbers.
std::vector<long> whole_turns(const std::vector<FinishedPath>& done) {
  std::vector<long> turns(done.size(), 0);
  for (std::size_t j = 1; j < done.size(); ++j) {
    const double ref = done[0].walker.q.theta_rad;
    const double theta = done[j].walker.q.theta_rad;
    turns[j] = std::lround((theta - (ref + std::remainder(theta - ref, 2.0 * kPi))) / (2.0 * kPi));
  }
  return turns;
}

/// equal_weight_ends within each group of paths that made the same whole
/// turns (`turns`, one per path), when more than one group has mass: the
/// groups' errors differ by the rotation-scale error of a whole turn (15
/// degrees at a 4 % scale error), so their true ends lie apart, each group
/// tight, while their odometric ends share the AtGoal circle and their
/// bearings overlap, and slabs by bearing averaged the groups into one
/// blob. Each group gets slabs in proportion to its mass (at least one),
/// `weights` each slab's probability; `weights` is left empty (equally
/// likely slabs) when there is one group. Found on generated gen_7582's
/// robot1 (tests/unit/verifier/data/turn_groups/spin_then_turn_about): its
/// last leg's goal lies 179 degrees behind it, 15 % of 1,000 runs turn left
/// and end 1.2 m from the rest (rotation scale 1.037), and the blob put 44 %
/// of the robot within 0.8 m of its goal where the runs put 17 % (now 25 %).
std::vector<Eigen::Vector2d> grouped_weight_ends(const std::vector<FinishedPath>& done, const std::vector<long>& turns,
                                                 const Eigen::Vector2d& goal, const Eigen::Vector2d& mean,
                                                 const Eigen::Vector2d& error_mean, std::size_t directions,
                                                 const std::vector<Eigen::Vector2d>& moved, std::vector<double>& weights) {
  weights.clear();
  double total = 0.0;
  std::map<long, double> group_mass;
  for (std::size_t i = 0; i < done.size(); ++i) {
    total += done[i].walker.weight;
    group_mass[i < turns.size() ? turns[i] : 0] += done[i].walker.weight;
  }
  std::size_t groups = 0;
  for (const auto& [g, m] : group_mass) groups += m > kMinTurnGroupShare * total ? 1 : 0;
  if (groups < 2) return equal_weight_ends(done, goal, mean, error_mean, directions, moved);
  std::vector<Eigen::Vector2d> out;
  for (const auto& [g, m] : group_mass) {
    if (!(m > 0.0)) continue;
    std::vector<FinishedPath> members;
    std::vector<Eigen::Vector2d> members_moved;
    for (std::size_t i = 0; i < done.size(); ++i) {
      if ((i < turns.size() ? turns[i] : 0) != g) continue;
      members.push_back(done[i]);
      if (!moved.empty()) members_moved.push_back(moved[i]);
    }
    const auto slabs = static_cast<std::size_t>(
        std::max<long>(1, std::lround(static_cast<double>(directions) * m / total)));
    for (const Eigen::Vector2d& d : equal_weight_ends(members, goal, mean, error_mean, slabs, members_moved)) {
      out.push_back(d);
      weights.push_back(m / total / static_cast<double>(slabs));
    }
  }
  return out;
}

/// The expected firing's phase for the held quadrature (trigger_phase.hpp):
/// each path's crossing time varies over its direction's arc by about the
/// difference to its neighbours' (the paths are on a circle of NOISE
/// directions), spread sd = |T_next - T_prev| / 2 / sqrt(12); the end pose is
/// moved, along the last step, from the half-cycle average settle_phase()
/// assumed to the firing that spread gives (the one deterministic check when
/// all paths are alike). One start point's paths at a time (their directions
/// are the circle).
void settle_phases(std::vector<FinishedPath>& done, std::size_t directions, std::size_t start) {
  std::vector<FinishedPath*> by_direction(directions, nullptr);
  for (FinishedPath& p : done) {
    if (p.start == start && p.direction < directions) by_direction[p.direction] = &p;
  }
  const auto crossing = [](const FinishedPath& p) {
    return static_cast<double>(p.walker.cycles) - 1.0 + std::max(p.crossing_c, 0.0);
  };
  const std::size_t n = directions;
  std::vector<double> offsets(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    FinishedPath* p = by_direction[j];
    if (!p || p->crossing_c < 0.0) continue;
    const FinishedPath* prev = by_direction[(j + n - 1) % n];
    const FinishedPath* next = by_direction[(j + 1) % n];
    double sd = 0.0;
    if (n > 1 && prev && next && prev->exit == p->exit && next->exit == p->exit) {
      sd = std::abs(crossing(*next) - crossing(*prev)) / 2.0 / std::sqrt(12.0);
    } else if (n > 1) {
      sd = 1.0;  // neighbours that leave differently: the direction's arc spans a lot
    }
    // The odometry's own jitter moves the crossing too, independently.
    sd = std::hypot(sd, p->crossing_sd);
    const CheckGap gap = check_gap(crossing(*p), sd);
    offsets[j] = crossing(*p) + gap.mean - static_cast<double>(p->walker.cycles);
    p->phase_var = gap.var;
  }
  for (std::size_t j = 0; j < n; ++j) {
    FinishedPath* p = by_direction[j];
    if (!p || p->crossing_c < 0.0) continue;
    const double move = offsets[j] - p->phase_cycles;
    p->walker.q.x_m += move * p->step(0);
    p->walker.q.y_m += move * p->step(1);
    p->walker.q.theta_rad += move * p->step(2);
    p->phase_cycles = offsets[j];
  }
}

/// Start points moved as the mean moved from `from` to `to` (a Spin's turn, a
/// still state's braking: every point alike), with the mean's end velocities.
std::vector<StartPoint> carried_along(const std::vector<StartPoint>& points, const BaseState& from, const BaseState& to) {
  std::vector<StartPoint> out;
  for (StartPoint p : points) {
    p.q.x_m += to.x_m - from.x_m;
    p.q.y_m += to.y_m - from.y_m;
    p.q.theta_rad += to.theta_rad - from.theta_rad;
    p.q.trans_mps = to.trans_mps;
    p.q.rot_radps = to.rot_radps;
    out.push_back(p);
  }
  return out;
}

/// How far the odometric base moves from q until it is at rest with both
/// velocities commanded to zero: the run-out of a robot stopped in a final or
/// still state, braked as analyze_still brakes it.
Eigen::Vector2d run_out(BaseState q, const Kinematics& k) {
  const double x0 = q.x_m, y0 = q.y_m;
  for (int cycle = 0; cycle < 1000 && !at_rest(q); ++cycle) step_cycle(q, 0.0, 0.0, k);
  return {q.x_m - x0, q.y_m - y0};
}

/// Equally likely points' durations (cycles) as seconds from their mean.
std::vector<double> centred_delays(const std::vector<double>& cycles, double cycle_s) {
  double mean = 0.0;
  for (const double c : cycles) mean += c / static_cast<double>(cycles.size());
  std::vector<double> out;
  for (const double c : cycles) out.push_back((c - mean) * cycle_s);
  return out;
}

/// Each finished path's probability (summing to 1), or nothing when they are
/// all equal (the points' weights are then implied: one over their number).
std::vector<double> path_weights(const std::vector<FinishedPath>& done) {
  double total = 0.0;
  bool equal = true;
  for (const FinishedPath& p : done) {
    total += p.walker.weight;
    equal = equal && p.walker.weight == done.front().walker.weight;
  }
  if (equal || !(total > 0.0)) return {};
  std::vector<double> out;
  for (const FinishedPath& p : done) out.push_back(p.walker.weight / total);
  return out;
}

/// The covariance of points about the origin: equal weights, or `weights`.
Eigen::Matrix2d points_cov(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& weights) {
  Eigen::Matrix2d c = Eigen::Matrix2d::Zero();
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (weights.empty()) {
      c += points[j] * points[j].transpose() / static_cast<double>(points.size());
    } else {
      c += weights[j] * points[j] * points[j].transpose();
    }
  }
  return c;
}

/// Where finished paths come to rest, each braking on its own from the speed
/// and heading it fired at: `centre` is their weighted mean (true positions:
/// odometric end plus run-out plus the error's deviation from the paths'
/// mean error), `offsets` points relative to it (one per path, in direction
/// order, when `one_per_path`, else equal_weight_ends' equally likely slabs),
/// `within` the spread the points average away.
struct RestPoints {
  std::vector<Eigen::Vector2d> offsets;
  /// Each offset's probability when one per path and the paths' weights
  /// differ (path_weights); empty when the points are equally likely.
  std::vector<double> weights;
  /// Each offset's path's duration in cycles (uncentred), when one per
  /// path and equally likely; empty for slabs and weighted points (their
  /// delays are not kept: see end_delays).
  std::vector<double> delays;
  Eigen::Matrix2d within = Eigen::Matrix2d::Zero();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
};

RestPoints rest_points(const std::vector<FinishedPath>& done, const std::vector<long>& turns, bool one_per_path,
                       const Eigen::Vector2d& goal, std::size_t directions, const Kinematics& k) {
  RestPoints out;
  double total = 0.0;
  Eigen::Vector2d error_mean = Eigen::Vector2d::Zero();
  for (const FinishedPath& p : done) {
    total += p.walker.weight;
    error_mean += p.walker.weight * p.walker.error.mean.head<2>();
  }
  if (done.empty() || !(total > 0.0)) return out;
  error_mean /= total;
  std::vector<Eigen::Vector2d> moved, at;
  for (const FinishedPath& p : done) {
    moved.push_back(run_out(p.walker.q, k));
    at.push_back(Eigen::Vector2d(p.walker.q.x_m, p.walker.q.y_m) + p.walker.error.mean.head<2>() - error_mean + moved.back());
    out.centre += (p.walker.weight / total) * at.back();
  }
  if (one_per_path) {
    for (const Eigen::Vector2d& x : at) out.offsets.push_back(x - out.centre);
    out.weights = path_weights(done);
    if (out.weights.empty()) {
      for (const FinishedPath& p : done) out.delays.push_back(static_cast<double>(p.walker.cycles));
    }
  } else {
    out.offsets = grouped_weight_ends(done, turns, goal, out.centre, error_mean, directions, moved, out.weights);
  }
  Eigen::Matrix2d all = Eigen::Matrix2d::Zero(), shown = Eigen::Matrix2d::Zero();
  for (std::size_t j = 0; j < done.size(); ++j) {
    all += (done[j].walker.weight / total) * (at[j] - out.centre) * (at[j] - out.centre).transpose();
  }
  shown = points_cov(out.offsets, out.weights);
  out.within = floored_psd(all - shown);
  // Where within its last cycle each path fires (the check comes 0..1 cycle
  // after the crossing): a spread along that cycle's step, 4 cm long at
  // 0.4 m/s, which the paths' ends at their expected firing do not show.
  for (const FinishedPath& p : done) {
    const Eigen::Vector2d step = p.step.head<2>();
    out.within += (p.walker.weight / total) * p.phase_var * step * step.transpose();
  }
  return out;
}

/// Which way (and how far) a robot at q must turn to face the state's goal
/// (GoToGuarded), or its heading relative to `ref` (Spin): the order in which
/// start points are merged, so that robots turning left and robots turning
/// right stay apart.
double entry_key(const BaseState& q, const mission::GoToGuardedParams* go, double ref_theta) {
  if (go != nullptr) return std::remainder(std::atan2(go->goal.y_m - q.y_m, go->goal.x_m - q.x_m) - q.theta_rad, 2.0 * kPi);
  return std::remainder(q.theta_rad - ref_theta, 2.0 * kPi);
}

/// The walkers a motion state's paths start from: the robot's start points
/// (recentred on `start`, the mean the sequencer carries), merged to at most
/// kStartPointsEntered in entry_key's order, each with the common error plus
/// its own explained offset; one walker at `start` when there are no points
/// or they all but coincide (a still robot, a leg without spread).
std::vector<Walker> entry_walkers(const mission::GoToGuardedParams* go, const BaseState& start,
                                  const ErrorState& error_start, const std::vector<StartPoint>& points) {
  Walker one;
  one.q = start;
  one.before = start;
  one.error = error_start;
  if (points.size() <= 1) return {one};
  const double n = static_cast<double>(points.size());
  StartPoint mean;
  mean.q = BaseState{};
  for (const StartPoint& p : points) {
    mean.q.x_m += p.q.x_m / n;
    mean.q.y_m += p.q.y_m / n;
    mean.q.theta_rad += (start.theta_rad + std::remainder(p.q.theta_rad - start.theta_rad, 2.0 * kPi)) / n;
    mean.q.trans_mps += p.q.trans_mps / n;
    mean.q.rot_radps += p.q.rot_radps / n;
    mean.error_offset += p.error_offset / n;
  }
  std::vector<StartPoint> centred;
  double reach = 0.0;
  for (const StartPoint& p : points) {
    StartPoint c = p;
    c.q.x_m += start.x_m - mean.q.x_m;
    c.q.y_m += start.y_m - mean.q.y_m;
    c.q.theta_rad = start.theta_rad + std::remainder(p.q.theta_rad - start.theta_rad, 2.0 * kPi) +
                    (start.theta_rad - mean.q.theta_rad);
    c.q.trans_mps += start.trans_mps - mean.q.trans_mps;
    c.q.rot_radps += start.rot_radps - mean.q.rot_radps;
    c.error_offset -= mean.error_offset;
    reach = std::max(reach, std::hypot(c.q.x_m - start.x_m, c.q.y_m - start.y_m) +
                                0.3 * std::abs(c.q.theta_rad - start.theta_rad) + c.error_offset.head<2>().norm());
    centred.push_back(c);
  }
  // Points within a few millimetres of each other make the same paths.
  if (reach < 0.005) return {one};
  std::vector<double> keys, weights(centred.size(), 1.0 / n);
  for (const StartPoint& p : centred) keys.push_back(entry_key(p.q, go, start.theta_rad));
  std::vector<StartPoint> merged;
  std::vector<double> merged_weights;
  if (go == nullptr) {
    merged = equal_weight_points(centred, weights, keys, kStartPointsEntered);
    merged_weights.assign(merged.size(), 1.0 / static_cast<double>(merged.size()));
  } else {
    // A robot facing about away from its goal turns left or right depending
    // on a few degrees of heading: the points stand for a continuous spread
    // (each as a small Gaussian in heading, of half the points' spread), and
    // the share of each beyond the flip (key = +-pi) turns the other way.
    // Then the left-turners and the right-turners are merged apart.
    double mean_theta = 0.0, var_theta = 0.0;
    for (const StartPoint& p : centred) mean_theta += p.q.theta_rad / n;
    for (const StartPoint& p : centred) var_theta += (p.q.theta_rad - mean_theta) * (p.q.theta_rad - mean_theta) / n;
    const double h = std::max(0.5 * std::sqrt(var_theta), 0.005);
    std::vector<StartPoint> side[2];
    std::vector<double> side_w[2], side_k[2];
    for (std::size_t i = 0; i < centred.size(); ++i) {
      const double k = keys[i];
      const double d = kPi - std::abs(k);  // how far from turning the other way
      const double flip = std::abs(k) > 0.5 * kPi ? normal_cdf(-d / h) : 0.0;
      const int s0 = k > 0.0 ? 0 : 1;
      if (flip < 1e-3) {
        side[s0].push_back(centred[i]);
        side_w[s0].push_back(weights[i]);
        side_k[s0].push_back(k);
        continue;
      }
      side[s0].push_back(centred[i]);
      side_w[s0].push_back(weights[i] * (1.0 - flip));
      side_k[s0].push_back(k);
      StartPoint other = centred[i];
      const double past = d + 0.8 * h;  // the tail's mass sits about this far across
      other.q.theta_rad -= (k > 0.0 ? 1.0 : -1.0) * past;
      side[1 - s0].push_back(other);
      side_w[1 - s0].push_back(weights[i] * flip);
      side_k[1 - s0].push_back(entry_key(other.q, go, start.theta_rad));
    }
    double total[2] = {0.0, 0.0};
    for (int g = 0; g < 2; ++g) {
      for (const double w : side_w[g]) total[g] += w;
    }
    const bool both = total[0] > 1e-3 && total[1] > 1e-3;
    for (int g = 0; g < 2; ++g) {
      if (!(total[g] > (both ? 1e-3 : 0.0))) continue;
      const std::size_t count = both ? kStartPointsEntered / 2 : kStartPointsEntered;
      for (const StartPoint& p : equal_weight_points(side[g], side_w[g], side_k[g], count)) {
        merged.push_back(p);
        merged_weights.push_back(total[g] / static_cast<double>(std::min(count, side[g].size())));
      }
    }
  }
  std::vector<Walker> out;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    Walker w;
    w.q = merged[i].q;
    w.before = merged[i].q;
    w.error = error_start;
    w.error.mean += merged[i].error_offset;
    w.weight = merged_weights[i];
    out.push_back(w);
  }
  return out;
}

/// Whether a NOISE redraw falls while some held path is still on its
/// approach: from `approach_cycles` before the fastest path fires to the
/// path's own firing. A held path is the robot under one draw for the whole
/// leg; it tells where the robot ends only if the approach sees one draw.
/// A direction that holds the robot off its goal (circling it in the
/// slow-down) is redrawn in a real run and leaves at another heading: on the
/// fresh sweep's gen_5157 robot1's first leg (dropoff 1.55 m, gain 0.125,
/// persistence 170) half the held paths outlast the first redraw, and 12 %
/// of 1,000 runs leave facing 60-100 degrees further left than any held path.
bool redrawn_on_approach(const NoiseQuadrature& held, std::int64_t persistence, double approach_cycles) {
  if (persistence <= 0 || held.finished.empty()) return false;
  std::size_t fastest = held.finished.front().walker.cycles;
  for (const FinishedPath& p : held.finished) fastest = std::min(fastest, p.walker.cycles);
  const double from = std::max(0.0, static_cast<double>(fastest) - approach_cycles);
  const auto draw = [&](double cycles) { return std::floor(cycles / static_cast<double>(persistence)); };
  return std::any_of(held.finished.begin(), held.finished.end(), [&](const FinishedPath& p) {
    return draw(static_cast<double>(p.walker.cycles)) > draw(from);
  });
}

StateAnalysis analyze_motion(const StateContext& ctx, std::size_t state, const BaseState& start,
                             const ErrorState& error_start, const std::vector<StartPoint>& start_points) {
  const mission::RobotSpec& robot = *ctx.robot;
  const PathStepper stepper(ctx, state);
  const auto* go = stepper.go();
  const bool noisy = go != nullptr && go->noise_gain != 0.0;
  const std::int64_t persistence = noisy ? go->noise_persistence_cycles : 0;
  const double cycle_s = ctx.model->kinematics.cycle_s;
  // (Twice the directions for short held legs brought
  // tests/data/accuracy/short_legs' time curve from 0.059 to 0.047, but
  // doubled bench_verifier's CPU: Bounding Overwatch's point 11 -> 19 ms,
  // relay 32 x 20 0.66 -> 1.3 s. Not done.)
  const std::size_t directions = noisy ? std::max<std::size_t>(1, ctx.models->budget.noise_sigma_points) : 1;

  // A Spin turns every start point alike (in place, by the same odometric
  // angle): one path from the mean, and its start points carried through
  // below, rather than a path per point.
  std::vector<Walker> entries =
      entry_walkers(go, start, error_start, go != nullptr ? start_points : std::vector<StartPoint>{});
  // Where a wall is within reach of the entry error's tail, the tail's runs
  // may be pinned where the mean's get through (engine/error_strata.hpp).
  std::size_t probe_cycles = 0;
  std::optional<Eigen::Vector3d> strata_axis;  // set where the entries are split
  std::vector<Walker> unsplit;
  if (go != nullptr) {
    if (const auto axis = wall_sensitive_axis(start, *go, error_start, ctx.walls, stepper.avoid_reach_m());
        axis && strata_may_differ(stepper, entries, *axis, directions, cycle_cap(ctx, state, start), probe_cycles)) {
      strata_axis = axis;
      unsplit = entries;
      entries = split_into_strata(entries, *axis);
    }
  }
  // Walkers kept between redraws: four per direction. Measured on
  // tests/data/accuracy/noise_redrawn_leg (2,000 runs): 8 kept gave a radius
  // curve 0.24 off (each merge of the lateral spread distorts the end arc),
  // 16 kept 0.06, 32 kept 0.039; with fewer kept far from the goal only the
  // radius went back to 0.069. Without a redraw (persistence at least the
  // leg) nothing is merged and this is the held quadrature.
  const std::size_t keep = 4 * directions;
  const std::size_t cap = cycle_cap(ctx, state, start);
  // A state a message can interrupt keeps each direction's pose versus time
  // (engine/interruption): from the first draw when nothing redraws, else
  // from the held quadrature (one direction per path for the whole state).
  const bool interruptible = has_trigger_kind(robot, state, mission::TriggerKind::notified);
  auto trajectory = interruptible ? std::make_shared<LegTrajectory>() : nullptr;
  if (trajectory) trajectory->cycle_s = cycle_s;
  NoiseQuadrature quad =
      noise_quadrature(stepper, entries, persistence, directions, keep, keep, cap, trajectory.get());

  // A stratum's stuck share is its mean's: a stratum pinned between two that
  // get through is read along the axis (engine/stuck_profile.hpp).
  if (strata_axis) probe_cycles += read_stuck_along_axis(stepper, unsplit, *strata_axis, persistence, directions, cap, quad);

  StateAnalysis a;
  a.cycles_simulated = quad.cycles_simulated + probe_cycles;
  a.blocked = quad.stuck;
  a.blocked_x_m = quad.stuck_x_m;  // divided by `blocked` below (where it is reported)
  a.blocked_y_m = quad.stuck_y_m;
  // Where the state ends (pose, error, end points): from the held-direction
  // quadrature when one draw lasts over the whole approach (the draw held at
  // full speed covers twice the slow-down) and every held path finishes,
  // from the segment quadrature otherwise. Measured: concurrent_moves' race leg
  // (16 m, redrawn once or twice) ends 1.0156 m from its goal with the held
  // paths, 1.0216 m with the segment quadrature, 1.0155 m in 2,000
  // validation runs; the radius curve there rises within 6 cm, so 6 mm is
  // 0.05 of it. Where a held direction pins the robot (a strong NOISE in a
  // long slow-down) there are no held ends to use, and where a held path is
  // still on its approach when the real NOISE is redrawn
  // (redrawn_on_approach) its end is not one a run reaches.
  NoiseQuadrature held;
  NoiseQuadrature* ends = &quad;
  const double approach_cycles =
      go != nullptr ? 2.0 * go->dropoff_m / std::max(robot.max_speed_mps, 1e-3) / cycle_s : 0.0;
  const bool draw_spans_approach = go != nullptr && static_cast<double>(persistence) >= approach_cycles;
  if (quad.redraws > 0 && (draw_spans_approach || trajectory)) {
    held = noise_quadrature(stepper, entries, 0, directions, directions, directions, cap, trajectory.get());
    a.cycles_simulated += held.cycles_simulated;
    if (draw_spans_approach && held.stuck <= 0.0 && !redrawn_on_approach(held, persistence, approach_cycles)) ends = &held;
    // The held paths at the redrawn robot's pace (engine/trajectory_pace.hpp).
    if (trajectory) {
      trajectory->path_time_s = path_times_at_pace(*trajectory, quad.mean_path);
      trajectory->redrawn_cov_m2 = redrawn_spreads(quad.mean_path, trajectory->path_time_s.size());
    }
  }
  // The sequencer sends the paths that got through on with the exits and
  // the stuck ones to wait for the message (engine/interruption.hpp,
  // trajectory_subset): split once here, where the analysis is cached.
  // Under a redrawn NOISE the trajectories are the held quadrature's, whose
  // stuck share can be far above the redrawn one (`a.blocked`, the share that
  // waits): a redraw frees most runs a held direction would pin. Those runs
  // get through, but until then they are on the pinned paths' way, so the
  // robots that get through are on every held path, a stuck one weighted by
  // the share it frees. With the paths that got through alone, gen_7026's
  // robot1 (NOISE 0.28, 5 of 8 held directions pinned by the walls, recalled
  // after 4.5 s) was 9 cm too far along its leg with a third of the runs'
  // spread (verify 7.264 +- 0.029 m from its goal, 400 runs 7.359 +- 0.090 m).
  if (trajectory) {
    const auto& stuck = trajectory->stuck;
    const bool any_stuck = std::any_of(stuck.begin(), stuck.end(), [](char c) { return c != 0; });
    const bool all_stuck = any_stuck && std::all_of(stuck.begin(), stuck.end(), [](char c) { return c != 0; });
    double held_stuck = 0.0;
    for (std::size_t j = 0; j < trajectory->paths.size(); ++j) held_stuck += trajectory->is_stuck(j) ? trajectory->weight(j) : 0.0;
    const double escaped = held_stuck > 0.0 ? std::clamp((held_stuck - a.blocked) / held_stuck, 0.0, 1.0) : 0.0;
    a.trajectory = any_stuck && !all_stuck ? trajectory_getting_through(*trajectory, escaped) : trajectory;
    if (any_stuck) a.stuck_trajectory = all_stuck ? trajectory : trajectory_subset(*trajectory, /*stuck=*/true);
  }
  if (ends->redraws == 0) {
    for (std::size_t s = 0; s < entries.size(); ++s) settle_phases(ends->finished, directions, s);
  }
  // Headings are continuous per path, but two paths that turned around in
  // opposite directions end a whole turn apart (+pi and -pi): averaged as
  // numbers they would face the other way. Bring every end heading within pi
  // of the first finished path's, remembering the whole turns between them
  // (error_given_end keeps those groups' errors apart).
  // (The segment quadrature's own turns too, before they are wrapped, where
  // its paths give the rest points' shape below.)
  const std::vector<long> quad_turns = whole_turns(quad.finished);
  const std::vector<long> turns = ends == &quad ? quad_turns : whole_turns(ends->finished);
  for (std::size_t j = 1; j < ends->finished.size(); ++j) {
    const double ref = ends->finished[0].walker.q.theta_rad;
    double& theta = ends->finished[j].walker.q.theta_rad;
    theta = ref + std::remainder(theta - ref, 2.0 * kPi);
  }
  double finished = 0.0;
  for (const FinishedPath& p : ends->finished) {
    const double w = p.walker.weight;
    finished += w;
    a.end.x_m += w * p.walker.q.x_m;
    a.end.y_m += w * p.walker.q.y_m;
    a.end.theta_rad += w * p.walker.q.theta_rad;
    a.end.trans_mps += w * p.walker.q.trans_mps;
    a.end.rot_radps += w * p.walker.q.rot_radps;
  }
  if (a.blocked > 0.0) {
    a.blocked_x_m /= a.blocked;
    a.blocked_y_m /= a.blocked;
  }
  if (finished <= 0.0) {
    a.end = start;
    a.error = error_start;
    a.path = quad.mean_path;
    return a;
  }
  a.end.x_m /= finished;
  a.end.y_m /= finished;
  a.end.theta_rad /= finished;
  a.end.trans_mps /= finished;
  a.end.rot_radps /= finished;
  const Eigen::Vector2d mean_xy(a.end.x_m, a.end.y_m);
  std::vector<Eigen::Vector3d> explained;
  a.error = error_given_end(ends->finished, turns, &a.error_paths, &explained);
  {
    // Where the state leaves the robot, for the next state's entry.
    std::vector<StartPoint> points;
    std::vector<double> weights, keys;
    // In the order that matters to what comes next: the turn toward the
    // next leg's goal (left-turners and right-turners apart; averaged by
    // place they made one heading, and every path then turned the same way),
    // the heading when a Spin carries it on, else where around the goal.
    const NextTurn next = next_turn(robot, state);
    const double centre =
        go != nullptr ? std::atan2(a.end.y_m - go->goal.y_m, a.end.x_m - go->goal.x_m) : a.end.theta_rad;
    for (std::size_t j = 0; j < ends->finished.size(); ++j) {
      const Walker& w = ends->finished[j].walker;
      points.push_back({w.q, explained[j]});
      weights.push_back(w.weight);
      if (go == nullptr || next.kind == NextTurn::Kind::spin) {
        keys.push_back(w.q.theta_rad - a.end.theta_rad);
      } else if (next.kind == NextTurn::Kind::leg) {
        keys.push_back(entry_key(w.q, next.leg, a.end.theta_rad));
      } else {
        keys.push_back(std::remainder(std::atan2(w.q.y_m - go->goal.y_m, w.q.x_m - go->goal.x_m) - centre, 2.0 * kPi));
      }
    }
    a.end_points = equal_weight_points(points, weights, keys, kStartPointsCarried);
    if (go == nullptr && start_points.size() > 1) {
      // The spin's start points, turned with it: the heading spread it came
      // with is what the next leg's turn toward its goal depends on.
      a.end_points = carried_along(start_points, start, a.end);
    }
  }
  if (go) {
    a.sets_spread = true;
    for (const FinishedPath& p : ends->finished) {
      const Eigen::Vector2d d = Eigen::Vector2d(p.walker.q.x_m, p.walker.q.y_m) - mean_xy;
      a.end_spread += (p.walker.weight / finished) * d * d.transpose();
    }
    // Where each path really ends (its odometric end plus its error's
    // deviation from the mean error: the two are correlated, so they are
    // added per path, not combined as independent spreads).
    const Eigen::Vector2d error_mean = a.error.mean.head<2>();
    // A point per path when there are few: a NOISE held for the whole leg
    // from one start point (a path per direction), or no NOISE from several
    // (a path per start point). Those ends lie on an arc around the goal, at
    // about the AtGoal radius from their own bearings; one slab for a leg
    // without NOISE made that arc one Gaussian blob, whose distance from the
    // goal spread where the runs' does not (gen_7370's robot1: 0.043 m
    // against the runs' 0.012 m, the radius curve 0.35 off).
    const bool one_per_path = ends->redraws == 0 && (entries.size() == 1 || directions == 1);
    std::vector<double> end_cycles;
    if (one_per_path) {
      // One end point per direction, in direction order (equal weights), or
      // per start point without NOISE (weighted as the start points were).
      for (const FinishedPath& p : ends->finished) {
        a.end_offsets.push_back(Eigen::Vector2d(p.walker.q.x_m, p.walker.q.y_m) + p.walker.error.mean.head<2>() - error_mean -
                                mean_xy);
        end_cycles.push_back(static_cast<double>(p.walker.cycles));
      }
      a.end_weights = path_weights(ends->finished);
      if (!a.end_weights.empty()) end_cycles.clear();
    } else {
      a.end_offsets = grouped_weight_ends(ends->finished, turns, Eigen::Vector2d(go->goal.x_m, go->goal.y_m), mean_xy,
                                          error_mean, directions, {}, a.end_weights);
    }
    // Which path fired when, for the final position's time scores: only where
    // each point is one path (a NOISE held for the whole leg). A redrawn
    // NOISE's slabs group paths by bearing, whose mean delays were tried and
    // not kept (docs/verifier.md, "Time and position together").
    a.end_delays = centred_delays(end_cycles, ctx.model->kinematics.cycle_s);
    // What the points do not show: the true ends' spread within each slab.
    Eigen::Matrix2d all = Eigen::Matrix2d::Zero(), shown = Eigen::Matrix2d::Zero();
    for (const FinishedPath& p : ends->finished) {
      const Eigen::Vector2d d =
          Eigen::Vector2d(p.walker.q.x_m, p.walker.q.y_m) + p.walker.error.mean.head<2>() - error_mean - mean_xy;
      all += (p.walker.weight / finished) * d * d.transpose();
    }
    shown = points_cov(a.end_offsets, a.end_weights);
    a.end_offsets_within = floored_psd(all - shown);

    // Where each path comes to rest when its exit stops the robot (a still
    // or final state): its own run-out, from the speed and heading it fired
    // at. The next state brakes the mean (a.end) alike for every point, which
    // put every path's end the same run-out along and lost the spread of the
    // braking distance (a NOISE pushing forward or aside at the AtGoal circle
    // fires at 0.15 or 0.36 m/s: 2 or 11 cm of run-out): the points are
    // relative to where the mean comes to rest.
    const bool stops_after =
        std::any_of(robot.states[state].outgoing.begin(), robot.states[state].outgoing.end(),
                    [&](std::size_t t) { return brakes_to_rest(robot, robot.transitions[t].to, ctx.model->kinematics); });
    if (stops_after) {
      const Eigen::Vector2d goal(go->goal.x_m, go->goal.y_m);
      const Kinematics& kin = ctx.model->kinematics;
      const RestPoints at_ends = rest_points(ends->finished, turns, one_per_path, goal, directions, kin);
      // Where the paths come to rest is centred where `ends` says (the held
      // paths when one draw spans the approach: where the circle is crossed);
      // but the speed and heading at the crossing are a redrawn NOISE's, not
      // the first draw's held to the end: when NOISE is redrawn in the leg,
      // the spread is the segment quadrature's. Measured against 1,000 runs
      // of tests/data/accuracy_open/noise_at_goal/variants/redrawn40.yaml
      // (held 40 cycles, once or twice redrawn): the held paths' spread gave
      // a radius curve 0.33 off, the segment quadrature's 0.12; on the fresh
      // sweep's gen_5126 (600 runs) it goes the other way, 0.087 against
      // 0.259, but the sweep as a whole favours it (docs/crosscheck.md).
      const bool redrawn_shape = ends != &quad && quad.redraws > 0 && !quad.finished.empty();
      const RestPoints shape = redrawn_shape ? rest_points(quad.finished, quad_turns, false, goal, directions, kin) : at_ends;
      const Eigen::Vector2d centre = at_ends.centre - (mean_xy + run_out(a.end, kin));
      for (const Eigen::Vector2d& d : shape.offsets) a.rest_offsets.push_back(d + centre);
      a.rest_weights = shape.weights;
      a.rest_offsets_within = shape.within;
      a.rest_delays = centred_delays(shape.delays, kin.cycle_s);
    }
  }

  // Durations per exit, in whole cycles (the executive checks its triggers
  // once per cycle).
  for (const std::size_t t : robot.states[state].outgoing) {
    double mass = 0.0;
    for (const FinishedPath& p : quad.finished) {
      if (p.exit == t) mass += p.walker.weight;
    }
    if (mass <= 0.0) continue;
    // The first draw's firings: each start point's directions are a circle
    // of their own, over which the duration is interpolated (held_duration).
    // A redrawn NOISE's later firings are a cloud of merged walkers, each
    // given a kernel (redrawn_duration_by_draw). Before, the first draw's
    // firings went into that cloud too whenever the leg ran past one redraw:
    // the kernel spread them below the fastest direction's time (crosscheck
    // gen_7568's first leg, held 130 cycles: verify P(t <= 7.25 s) 0.050
    // where no run of 2,000 had finished).
    Mixture1 duration;
    std::map<std::size_t, HeldCircle> circles;
    std::vector<double> values, ws;
    std::vector<std::size_t> segments;
    double later_mass = 0.0;
    const auto circle_of = [&](std::size_t from) -> HeldCircle& {
      HeldCircle& c = circles[from];
      if (c.fired.empty()) {
        c.fired.assign(directions, nullptr);
        // Redrawn: a direction that ended nothing under the first draw was
        // still running at its end.
        c.running.assign(directions, quad.redraws > 0);
        c.draw_end_cycles = static_cast<double>(persistence);
        c.exit = t;
        for (const ProbedCircle& probed : quad.probed) {
          if (probed.start == from) c.probed = &probed;
        }
      }
      return c;
    };
    for (const FinishedPath& p : quad.finished) {
      if (p.segment == 0 && p.direction < directions) {
        HeldCircle& circle = circle_of(p.start);
        circle.running[p.direction] = false;
        if (p.exit == t) circle.fired[p.direction] = &p;
        continue;
      }
      if (p.exit != t) continue;
      values.push_back(static_cast<double>(p.walker.cycles) * cycle_s);
      ws.push_back(p.walker.weight);
      segments.push_back(p.segment);
      later_mass += p.walker.weight;
    }
    const auto add_part = [&duration](const Mixture1& part, double part_mass) {
      for (const Component1& c : part.components) duration.components.push_back({c.weight * part_mass, c.mean, c.var});
    };
    for (const auto& entry : circles) {
      const HeldCircle& circle = entry.second;
      double mass_s = 0.0;
      for (const FinishedPath* p : circle.fired) mass_s += p ? p->walker.weight : 0.0;
      if (mass_s > 0.0) add_part(held_duration(circle, cycle_s, ctx.models->budget.max_components), mass_s);
    }
    if (later_mass > 0.0) {
      add_part(redrawn_duration_by_draw(values, ws, segments, static_cast<double>(persistence) * cycle_s,
                                        ctx.models->budget.max_components),
               later_mass);
    }
    duration.normalise();
    reduce(duration, ctx.models->budget.max_components);
    a.exits.push_back({t, mass, std::move(duration)});
  }
  a.path = quad.mean_path;
  return a;
}

/// Stop / Notify: zero command; the base brakes to rest (carried over if the
/// state is shorter than the braking, which the next state then continues).
StateAnalysis analyze_still(const StateContext& ctx, std::size_t state, const BaseState& start,
                            const ErrorState& error_start, const std::vector<StartPoint>& start_points) {
  const mission::RobotSpec& robot = *ctx.robot;
  const Kinematics& k = ctx.model->kinematics;
  StateAnalysis a;
  a.end = start;
  a.error = error_start;
  std::size_t braking_cycles = 0;
  const bool timed_by_ack = has_trigger_kind(robot, state, mission::TriggerKind::message_sent);
  Mixture1 ack;
  std::size_t modal_cycles = 1000;
  if (timed_by_ack) {
    ack = delay_in_cycles(ctx.models->comm.ack_s, k.cycle_s, ctx.models->budget.max_components);
    // Brake for the most likely number of cycles the state lasts.
    double best = -1.0;
    for (const Component1& c : ack.components) {
      if (c.weight > best) {
        best = c.weight;
        modal_cycles = static_cast<std::size_t>(std::max(1.0, std::round(c.mean / k.cycle_s)));
      }
    }
  }
  while (!at_rest(a.end) && braking_cycles < modal_cycles && braking_cycles < 1000) {
    const CycleIncrement inc = step_cycle(a.end, 0.0, 0.0, k);
    propagate(a.error, inc, ctx.model->motion);
    ++braking_cycles;
  }
  a.cycles_simulated = braking_cycles;
  // The start points brake the way the mean does (a still robot's points
  // only carry on to the next motion state).
  a.end_points = carried_along(start_points, start, a.end);

  // Self-timed exits on a still robot fire on the first check or never.
  for (const std::size_t t : robot.states[state].outgoing) {
    const mission::Transition& tr = robot.transitions[t];
    if (tr.kind() == mission::TriggerKind::message_sent) {
      a.exits.push_back({t, 1.0, ack});
      break;  // the first that can fire wins; later self-timed exits are shadowed
    }
    if (tr.kind() == mission::TriggerKind::at_goal || tr.kind() == mission::TriggerKind::has_turned) {
      if (fired_exit(robot, state, start, 0.0) == t) {
        a.exits.push_back({t, 1.0, Mixture1::point(k.cycle_s)});
        break;
      }
    }
  }
  const bool waits = has_trigger_kind(robot, state, mission::TriggerKind::notified);
  if (a.exits.empty() && !waits && !robot.is_final(state)) {
    a.blocked = 1.0;
    a.blocked_x_m = start.x_m;
    a.blocked_y_m = start.y_m;
  }
  return a;
}

}  // namespace

Mixture1 delay_in_cycles(const Mixture1& delay_s, double cycle_s, std::size_t max_components) {
  if (delay_s.components.empty()) return Mixture1::point(cycle_s);
  std::vector<double> values, weights;
  double previous = 0.0;
  for (std::size_t j = 1; j <= 6000; ++j) {
    const double cdf = delay_s.cdf(static_cast<double>(j) * cycle_s);
    const double mass = (j == 1 ? cdf : cdf - previous);
    previous = cdf;
    if (mass > 1e-12) {
      values.push_back(static_cast<double>(j) * cycle_s);
      weights.push_back(mass);
    }
    if (1.0 - cdf < 1e-9) break;
  }
  if (values.empty()) return Mixture1::point(cycle_s);
  return from_weighted_points(values, weights, max_components);
}

StateAnalysis analyze_state(const StateContext& context, std::size_t state_index, const BaseState& start,
                            const ErrorState& error_start, const std::vector<StartPoint>& start_points) {
  const mission::BehaviorKind kind = context.robot->states[state_index].kind();
  StateAnalysis a;
  if (kind == mission::BehaviorKind::go_to_guarded || kind == mission::BehaviorKind::spin) {
    a = analyze_motion(context, state_index, start, error_start, start_points);
    // A motion state that also listens for messages is not stuck just because
    // its own triggers never fire: the sequencer weighs the message instead.
    if (has_trigger_kind(*context.robot, state_index, mission::TriggerKind::notified) && a.exits.empty()) a.blocked = 0.0;
  } else {
    a = analyze_still(context, state_index, start, error_start, start_points);
  }
  return a;
}

namespace {

/// Whether a Spin state certainly lasts until the robot's translation, which
/// it commands to zero, has braked to rest: every exit is a HasTurned whose
/// angle, at the rate the firmware allows, takes at least as long as braking
/// from the robot's top speed.
bool spin_outlasts_braking(const mission::RobotSpec& robot, std::size_t state, const Kinematics& kin) {
  const auto* spin = std::get_if<mission::SpinParams>(&robot.states[state].behavior);
  if (spin == nullptr || !(kin.trans_decel_mps2 > 0.0)) return false;
  const double rate_radps = std::min(std::abs(spin->rate_deg_s) * kDegToRad, kin.max_rot_vel_radps);
  if (!(rate_radps > 0.0)) return false;
  const double braking_s = robot.max_speed_mps / kin.trans_decel_mps2 + kin.cycle_s;
  const auto& out = robot.states[state].outgoing;
  return !out.empty() && std::all_of(out.begin(), out.end(), [&](std::size_t t) {
    const auto* turned = std::get_if<mission::HasTurnedParams>(&robot.transitions[t].trigger);
    return turned != nullptr && (turned->angle_deg - turned->offset_deg) * kDegToRad / rate_radps >= braking_s;
  });
}

/// Where the search of brakes_to_rest stands on an acknowledgement-timed state.
enum class StillSearch : unsigned char { unseen, on_path, braking, moving };

bool brakes_to_rest_from(const mission::RobotSpec& robot, std::size_t state, const Kinematics& kin,
                         std::vector<StillSearch>& seen) {
  if (robot.is_final(state)) return true;
  const mission::BehaviorKind kind = robot.states[state].kind();
  if (kind == mission::BehaviorKind::go_to_guarded) return false;
  // A Spin turns in place: the translation it comes in with brakes as in a
  // Stop, the heading turning under it, if the turn outlasts the braking
  // (a scout that turns to face the hall on arrival at 0.6 m/s runs out 2 to
  // 7 cm by its own firing speed: tests/data/accuracy/mixed_speeds).
  if (kind == mission::BehaviorKind::spin) return spin_outlasts_braking(robot, state, kin);
  if (!has_trigger_kind(robot, state, mission::TriggerKind::message_sent)) return true;
  // analyze_still brakes an acknowledgement-timed state (a Notify) only for
  // its most likely length, which may end before the robot is at rest; the
  // braking goes on in the state its acknowledgement leads to. If every such
  // state holds the robot still too (a Stop, another Notify, a long enough
  // Spin), the robot comes to rest before it moves again, wherever the
  // acknowledgement cut the Notify. A cycle of acknowledgement-timed states
  // is not counted; each state is searched once (a chain of Notifies with
  // several exits each would otherwise be walked once per path through it).
  if (seen[state] == StillSearch::on_path) return false;
  if (seen[state] != StillSearch::unseen) return seen[state] == StillSearch::braking;
  seen[state] = StillSearch::on_path;
  const auto& out = robot.states[state].outgoing;
  const bool braking = !out.empty() && std::all_of(out.begin(), out.end(), [&](std::size_t t) {
    return brakes_to_rest_from(robot, robot.transitions[t].to, kin, seen);
  });
  seen[state] = braking ? StillSearch::braking : StillSearch::moving;
  return braking;
}

}  // namespace

bool brakes_to_rest(const mission::RobotSpec& robot, std::size_t state, const Kinematics& kin) {
  std::vector<StillSearch> seen(robot.states.size(), StillSearch::unseen);
  return brakes_to_rest_from(robot, state, kin, seen);
}

StateAnalysis analyze_final(const StateContext& context, std::size_t state_index, const BaseState& start,
                            const ErrorState& error_start) {
  // A final state has no outgoing transition, so the still state's braking is all there is.
  return analyze_still(context, state_index, start, error_start, {});
}

std::vector<StartPoint> equal_weight_points(const std::vector<StartPoint>& points, const std::vector<double>& weights,
                                            const std::vector<double>& key, std::size_t n) {
  std::vector<StartPoint> out;
  double total = 0.0;
  for (const double w : weights) total += std::max(w, 0.0);
  n = std::min(n, points.size());
  if (points.empty() || n == 0 || !(total > 0.0)) return out;
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  const double slab = total / static_cast<double>(n);
  std::vector<StartPoint> sums(n);
  std::vector<double> masses(n, 0.0);
  for (StartPoint& p : sums) p.q = BaseState{};
  double c0 = 0.0;
  for (const std::size_t i : order) {
    const double w = std::max(weights[i], 0.0);
    const double c1 = c0 + w;
    const StartPoint& p = points[i];
    const double theta = p.q.theta_rad;  // continuous: the callers keep the points within pi of their mean
    const auto first = static_cast<std::size_t>(std::min(static_cast<double>(n - 1), std::floor(c0 / slab)));
    for (std::size_t k = first; k < n; ++k) {
      const double overlap = std::min(c1, static_cast<double>(k + 1) * slab) - std::max(c0, static_cast<double>(k) * slab);
      if (overlap <= 0.0) {
        if (static_cast<double>(k) * slab >= c1) break;
        continue;
      }
      StartPoint& s = sums[k];
      s.q.x_m += overlap * p.q.x_m;
      s.q.y_m += overlap * p.q.y_m;
      s.q.theta_rad += overlap * theta;
      s.q.trans_mps += overlap * p.q.trans_mps;
      s.q.rot_radps += overlap * p.q.rot_radps;
      s.error_offset += overlap * p.error_offset;
      masses[k] += overlap;
    }
    c0 = c1;
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!(masses[k] > 0.0)) continue;
    StartPoint p = sums[k];
    const double m = masses[k];
    p.q.x_m /= m;
    p.q.y_m /= m;
    p.q.theta_rad /= m;
    p.q.trans_mps /= m;
    p.q.rot_radps /= m;
    p.error_offset /= m;
    out.push_back(p);
  }
  return out;
}

}  // namespace p3at::verifier::engine
