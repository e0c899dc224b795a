#include "engine/state_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <type_traits>
#include <variant>

#include <Eigen/Cholesky>

#include "p3at/executive/behaviors.hpp"
#include "p3at/executive/frames.hpp"
#include "p3at/executive/sonar.hpp"
#include "engine/trigger_phase.hpp"

namespace p3at::verifier::engine {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
// Cycles a state may take, beyond its nominal length, before its path is
// declared stuck: generous, so a slow but moving robot is never called stuck.
constexpr std::size_t kMinCycleCap = 3000;

exec::BehaviorConfig behavior_config(const mission::RobotSpec& robot, const Kinematics& k) {
  exec::BehaviorConfig c;
  c.max_speed_mps = robot.max_speed_mps;
  c.max_rot_radps = k.max_rot_vel_radps;
  c.rot_gain = k.rot_gain;
  c.robot_radius_m = k.robot_radius_m;
  return c;
}

/// The self-timed triggers of the state's outgoing transitions, checked on
/// the odometric pose as the executive checks them. Returns the first that
/// holds, in file order (the executive's order), or nothing.
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

/// The executive checks a trigger once per cycle, and where in that cycle a
/// real run crosses the threshold (AtGoal's radius, HasTurned's angle) is as
/// good as random: a deterministic path has one phase, real runs all of them.
/// With the crossing a fraction c into the last cycle (linear between the two
/// checks), the check that fires comes uniformly 0..1 cycle after it: on
/// average at (c + 0.5) cycles into it, i.e. c - 0.5 cycles from the
/// deterministic firing. Returns that offset, in [-0.5, 0.5].
double crossing_phase(const mission::RobotSpec& robot, std::size_t transition, const BaseState& before,
                      const BaseState& now, double turned_before, double turned_now) {
  const mission::TriggerParams& trigger = robot.transitions[transition].trigger;
  double from = 0.0, to = 0.0, threshold = 0.0;
  if (const auto* g = std::get_if<mission::AtGoalParams>(&trigger)) {
    from = std::hypot(g->goal.x_m - before.x_m, g->goal.y_m - before.y_m);
    to = std::hypot(g->goal.x_m - now.x_m, g->goal.y_m - now.y_m);
    threshold = g->radius_m;
  } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
    from = -turned_before;  // decreasing toward -threshold, like a distance
    to = -turned_now;
    threshold = -(h->angle_deg - h->offset_deg) * kDegToRad;
  } else {
    return 0.0;
  }
  if (!(from > threshold) || !(from > to)) return 0.0;  // fired at once, or not by moving toward it
  const double c = std::clamp((from - threshold) / (from - to), 0.0, 1.0);
  return c - 0.5;
}

bool has_trigger_kind(const mission::RobotSpec& robot, std::size_t state, mission::TriggerKind kind) {
  return std::any_of(robot.states[state].outgoing.begin(), robot.states[state].outgoing.end(),
                     [&](std::size_t t) { return robot.transitions[t].kind() == kind; });
}

/// One path of a motion state under one noise direction.
struct PathResult {
  std::optional<std::size_t> exit;
  std::size_t cycles = 0;
  /// Where in its last cycle the path crossed its trigger's threshold, as the
  /// expected firing time's offset from `cycles` (see crossing_phase()); the
  /// end pose is the one at that expected firing.
  double phase_cycles = 0.0;
  /// The last cycle's step (end minus the pose one cycle earlier, before the
  /// phase move) and the crossing's fraction into it (-1: none), for
  /// settle_phases().
  double step_x = 0.0, step_y = 0.0, step_theta = 0.0, crossing_c = -1.0;
  BaseState end;
  ErrorState error;
  std::vector<PathSample> samples;
};

/// True when the crossing's fraction c (crossing_phase() + 1/2) is meaningful:
/// the trigger was crossed by moving toward it within the last cycle.
bool crossing_phase_known(const mission::RobotSpec& robot, std::size_t transition, const BaseState& before,
                          const BaseState& now, double turned_before, double turned_now) {
  const mission::TriggerParams& trigger = robot.transitions[transition].trigger;
  double from = 0.0, to = 0.0, threshold = 0.0;
  if (const auto* g = std::get_if<mission::AtGoalParams>(&trigger)) {
    from = std::hypot(g->goal.x_m - before.x_m, g->goal.y_m - before.y_m);
    to = std::hypot(g->goal.x_m - now.x_m, g->goal.y_m - now.y_m);
    threshold = g->radius_m;
  } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
    from = -turned_before;
    to = -turned_now;
    threshold = -(h->angle_deg - h->offset_deg) * kDegToRad;
  } else {
    return false;
  }
  return from > threshold && from > to;
}

/// The expected firing's phase (trigger_phase.hpp): each path's crossing time
/// varies over its quadrature node's arc by about the difference to its
/// neighbours' (paths are on a circle of NOISE directions), spread sd =
/// |T_next - T_prev| / 2 / sqrt(12); the end pose is moved, along the last
/// step, from the half-cycle average crossing_phase() assumed to the firing
/// that spread gives (the one deterministic check when all paths alike).
void settle_phases(std::vector<PathResult>& paths) {
  const std::size_t n = paths.size();
  std::vector<double> crossing(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    crossing[j] = static_cast<double>(paths[j].cycles) - 1.0 + std::max(paths[j].crossing_c, 0.0);
  }
  for (std::size_t j = 0; j < n; ++j) {
    PathResult& p = paths[j];
    if (!p.exit || p.crossing_c < 0.0) continue;
    const PathResult& prev = paths[(j + n - 1) % n];
    const PathResult& next = paths[(j + 1) % n];
    double sd = 0.0;
    if (n > 1 && prev.exit && next.exit && *prev.exit == *p.exit && *next.exit == *p.exit) {
      sd = std::abs(crossing[(j + 1) % n] - crossing[(j + n - 1) % n]) / 2.0 / std::sqrt(12.0);
    } else if (n > 1) {
      sd = 1.0;  // neighbours that leave differently: the node's arc spans a lot
    }
    const double offset = crossing[j] + expected_check_gap(crossing[j], sd) - static_cast<double>(p.cycles);
    const double move = offset - p.phase_cycles;
    p.end.x_m += move * p.step_x;
    p.end.y_m += move * p.step_y;
    p.end.theta_rad += move * p.step_theta;
    p.phase_cycles = offset;
  }
}

/// One path of the NOISE quadrature. `redraw_turn_rad` = 0: the direction is
/// held for the whole state; otherwise each redraw (every `persistence`
/// cycles) turns it by that angle, so the path passes through differing
/// directions as the real NOISE's redraws do.
PathResult run_path(const StateContext& ctx, std::size_t state, const BaseState& start, const ErrorState& error_start,
                    double noise_angle_rad, std::size_t cap, double redraw_turn_rad = 0.0,
                    std::vector<TrajectoryPoint>* record = nullptr) {
  const mission::RobotSpec& robot = *ctx.robot;
  const Kinematics& k = ctx.model->kinematics;
  const exec::BehaviorConfig config = behavior_config(robot, k);
  const mission::BehaviorParams& behavior = robot.states[state].behavior;
  const auto* go = std::get_if<mission::GoToGuardedParams>(&behavior);
  const auto* spin = std::get_if<mission::SpinParams>(&behavior);
  const std::size_t sample_every = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(1.0 / k.cycle_s)));
  const double max_range = ctx.models->environment.sonar_max_range_m;
  // How far from the robot's (true) centre an obstacle can still push it:
  // contact distance plus the sphere of influence, plus the sonar ring's
  // offset from the centre (a reading is the distance from the transducer),
  // plus a little for rounding.
  constexpr double kSonarOffsetM = 0.3;
  const double avoid_reach_m =
      go ? k.robot_radius_m + go->safety_margin_m + go->sphere_m + kSonarOffsetM + 0.05 : 0.0;

  PathResult r;
  r.end = start;
  r.error = error_start;
  double turned = 0.0, turned_before = 0.0;
  BaseState before = start;
  for (std::size_t n = 0;; ++n) {
    // Recorded until the robot has come to rest for good (a leg waiting at its
    // goal for a message): beyond the record the pose is held (pose_at), so a
    // long wait costs no memory.
    if (record != nullptr) {
      if (record->size() >= 2 && at_rest(r.end) && at_rest(record->back().base)) record = nullptr;  // for good: indices are cycles
      else record->push_back({r.end, r.error});
    }
    if (n >= 1) {
      if (const auto fired = fired_exit(robot, state, r.end, turned)) {
        r.exit = fired;
        r.cycles = n;
        // The pose at the expected firing, not at this path's phase: moved
        // along the last cycle's step by the phase offset. (The duration
        // stays in whole cycles: the orderings of events in the same cycle,
        // an acknowledgement racing a delivery, are decided in whole cycles.)
        r.phase_cycles = crossing_phase(robot, *fired, before, r.end, turned_before, turned);
        r.step_x = r.end.x_m - before.x_m;
        r.step_y = r.end.y_m - before.y_m;
        r.step_theta = r.end.theta_rad - before.theta_rad;
        if (crossing_phase_known(robot, *fired, before, r.end, turned_before, turned)) r.crossing_c = r.phase_cycles + 0.5;
        r.end.x_m += r.phase_cycles * (r.end.x_m - before.x_m);
        r.end.y_m += r.phase_cycles * (r.end.y_m - before.y_m);
        r.end.theta_rad += r.phase_cycles * (r.end.theta_rad - before.theta_rad);
        return r;
      }
    }
    if (n >= cap) {
      r.cycles = n;
      return r;
    }
    if (n % sample_every == 0) r.samples.push_back({static_cast<double>(n) * k.cycle_s, r.end.x_m, r.end.y_m});
    double trans = 0.0, rot = 0.0;
    if (go) {
      // The sonar sees the world from the true pose; the executive places what
      // it sees around its odometric pose.
      const double tx = r.end.x_m + r.error.mean(0), ty = r.end.y_m + r.error.mean(1);
      const double tth = r.end.theta_rad + r.error.mean(2);
      const exec::Pose<double> pose{r.end.x_m, r.end.y_m, r.end.theta_rad};
      exec::SonarObstacles<double> obstacles;
      // AVOID_OBSTACLES ignores anything beyond its reach, so when nothing is
      // that close the readings cannot matter and need not be cast (exact).
      if (nearest_distance(ctx.obstacles, tx, ty) <= avoid_reach_m) {
        const auto ranges = sonar_ranges(ctx.obstacles, tx, ty, tth, max_range);
        obstacles = exec::sonar_obstacles(std::span<const double, exec::kP3atSonarCount>(ranges), pose, max_range);
      }
      // The quadrature's direction for this path (see analyze_motion for
      // how held and redrawn paths are combined).
      const double draw =
          go->noise_persistence_cycles > 0 ? static_cast<double>(static_cast<std::int64_t>(n) / go->noise_persistence_cycles) : 0.0;
      const double angle = noise_angle_rad + draw * redraw_turn_rad;
      const exec::Vec2<double> noise{std::cos(angle), std::sin(angle)};
      const exec::Velocity<double> v = exec::go_to_guarded(*go, pose, obstacles.view(), noise, config);
      trans = v.trans_mps;
      rot = v.rot_radps;
    } else if (spin) {
      rot = exec::spin_command(*spin, config).rot_radps;
    }
    before = r.end;
    turned_before = turned;
    const CycleIncrement inc = step_cycle(r.end, trans, rot, k);
    propagate(r.error, inc, ctx.model->motion);
    turned += std::abs(exec::wrap_angle_rad(inc.dtheta_rad));
  }
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

/// The shrink factor for duration deviations when NOISE redraws during a
/// state: k independent draws over segments L_1..L_k spread the time by
/// sqrt(sum L_i^2) / sum L_i of one held draw's spread.
double redraw_shrink(std::size_t cycles, std::int64_t persistence) {
  if (persistence <= 0 || cycles <= static_cast<std::size_t>(persistence)) return 1.0;
  const double p = static_cast<double>(persistence);
  const double total = static_cast<double>(cycles);
  const double full = std::floor(total / p);
  const double rest = total - full * p;
  return std::sqrt(full * p * p + rest * rest) / total;
}

/// The error at the end of a motion state, carried forward from the MEAN
/// odometric end pose. The error is largely a function of the odometric pose
/// itself (a rotation-scale error is (k - 1) times the net odometric turn; a
/// distance-scale error grows with the odometric displacement), and the next
/// state re-steers from wherever odometry says the robot is. So the part of
/// the paths' error spread that is explained by their differing end poses is
/// not a spread the robot keeps: regress the paths' error means on their end
/// poses (weighted least squares) and carry only the residual spread, plus
/// each path's own (within-path) covariance.
ErrorState error_given_end(const std::vector<PathResult>& paths, double w) {
  std::vector<const PathResult*> done;
  for (const PathResult& p : paths) {
    if (p.exit) done.push_back(&p);
  }
  ErrorState out;
  if (done.empty()) return out;
  const double n = static_cast<double>(done.size());
  Eigen::Vector3d q_mean = Eigen::Vector3d::Zero();
  for (const PathResult* p : done) {
    out.mean += p->error.mean / n;
    q_mean += Eigen::Vector3d(p->end.x_m, p->end.y_m, p->end.theta_rad) / n;
  }
  // Centred regressors and responses; a small ridge keeps a degenerate
  // spread (all paths alike, or a straight line of end points) well posed.
  Eigen::MatrixXd x(done.size(), 3), y(done.size(), 3);
  for (std::size_t i = 0; i < done.size(); ++i) {
    x.row(static_cast<Eigen::Index>(i)) =
        (Eigen::Vector3d(done[i]->end.x_m, done[i]->end.y_m, done[i]->end.theta_rad) - q_mean).transpose();
    y.row(static_cast<Eigen::Index>(i)) = (done[i]->error.mean - out.mean).transpose();
  }
  const Eigen::Matrix3d xtx = x.transpose() * x + 1e-9 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d b = xtx.ldlt().solve(x.transpose() * y);  // y ≈ x b
  const Eigen::MatrixXd residual = y - x * b;
  for (std::size_t i = 0; i < done.size(); ++i) {
    const Eigen::Vector3d r = residual.row(static_cast<Eigen::Index>(i)).transpose();
    out.cov += (done[i]->error.cov + r * r.transpose()) / n;
  }
  (void)w;  // equal weights: every quadrature point has the same weight
  return out;
}

StateAnalysis analyze_motion(const StateContext& ctx, std::size_t state, const BaseState& start,
                             const ErrorState& error_start) {
  const mission::RobotSpec& robot = *ctx.robot;
  const auto* go = std::get_if<mission::GoToGuardedParams>(&robot.states[state].behavior);
  const bool noisy = go != nullptr && go->noise_gain != 0.0;
  const std::size_t points = noisy ? std::max<std::size_t>(1, ctx.models->budget.noise_sigma_points) : 1;
  const std::size_t cap = cycle_cap(ctx, state, start);
  const double cycle_s = ctx.model->kinematics.cycle_s;

  // A state a message can interrupt keeps each path's pose versus time.
  std::shared_ptr<LegTrajectory> trajectory;
  if (has_trigger_kind(robot, state, mission::TriggerKind::notified)) {
    trajectory = std::make_shared<LegTrajectory>();
    trajectory->cycle_s = cycle_s;
    trajectory->paths.resize(points);
  }
  std::vector<PathResult> paths;
  paths.reserve(points);
  for (std::size_t j = 0; j < points; ++j) {
    const double angle = 2.0 * kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(points);
    paths.push_back(run_path(ctx, state, start, error_start, angle, cap, 0.0,
                             trajectory ? &trajectory->paths[j] : nullptr));
  }

  settle_phases(paths);

  // Headings are continuous per path, but two paths that turned around in
  // opposite directions end a whole turn apart (+pi and -pi): averaged as
  // numbers they would face the other way. Bring every end heading within pi
  // of the first finished path's.
  for (std::size_t j = 1; j < paths.size(); ++j) {
    const double ref = paths[0].end.theta_rad;
    paths[j].end.theta_rad = ref + exec::wrap_angle_rad(paths[j].end.theta_rad - ref);
  }

  StateAnalysis a;
  a.trajectory = trajectory;
  const double w = 1.0 / static_cast<double>(points);
  std::vector<ErrorState> errors;
  std::vector<double> weights;
  Eigen::Vector2d mean_xy = Eigen::Vector2d::Zero();
  double finished = 0.0;
  for (const PathResult& p : paths) {
    a.cycles_simulated += p.cycles;
    if (!p.exit) {
      a.blocked += w;
      continue;
    }
    finished += w;
    errors.push_back(p.error);
    weights.push_back(w);
    mean_xy += w * Eigen::Vector2d(p.end.x_m, p.end.y_m);
    a.end.x_m += w * p.end.x_m;
    a.end.y_m += w * p.end.y_m;
    a.end.theta_rad += w * p.end.theta_rad;
    a.end.trans_mps += w * p.end.trans_mps;
    a.end.rot_radps += w * p.end.rot_radps;
  }
  if (finished <= 0.0) {
    a.end = start;
    a.error = error_start;
    return a;
  }
  a.end.x_m /= finished;
  a.end.y_m /= finished;
  a.end.theta_rad /= finished;
  a.end.trans_mps /= finished;
  a.end.rot_radps /= finished;
  mean_xy /= finished;
  a.error = error_given_end(paths, w);
  if (go) {
    a.sets_spread = true;
    for (const PathResult& p : paths) {
      if (!p.exit) continue;
      const Eigen::Vector2d d = Eigen::Vector2d(p.end.x_m, p.end.y_m) - mean_xy;
      a.end_spread += (w / finished) * d * d.transpose();
      a.end_offsets.push_back(d);
    }
  }

  // Durations per exit. The held paths above are the quadrature of one
  // NOISE draw; when NOISE redraws within the state, independent draws over
  // segments L_i spread the duration by sqrt(sum L_i^2) / sum L_i of one held
  // draw's spread (redraw_shrink), and the mean comes from paths whose
  // direction turns at each redraw (golden angle), since a redraw's new
  // transient lengthens the path in a way one held direction does not.
  // Turning the direction within the held paths as well would average the
  // redraws twice (on a 16 m leg redrawn every 30 s the spread came out a
  // third of the simulator's).
  const std::int64_t persistence = go ? go->noise_persistence_cycles : 0;
  std::vector<PathResult> redrawn;
  const bool redraws = noisy && persistence > 0 &&
                       std::any_of(paths.begin(), paths.end(), [&](const PathResult& p) {
                         return p.cycles > static_cast<std::size_t>(persistence);
                       });
  if (redraws) {
    constexpr double kGoldenAngleRad = 2.399963229728653;
    redrawn.reserve(points);
    for (std::size_t j = 0; j < points; ++j) {
      const double angle = 2.0 * kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(points);
      redrawn.push_back(run_path(ctx, state, start, error_start, angle, cap, kGoldenAngleRad));
      a.cycles_simulated += redrawn.back().cycles;
    }
  }
  for (const std::size_t t : robot.states[state].outgoing) {
    std::vector<double> values, ws;
    double mean = 0.0, mass = 0.0;
    for (const PathResult& p : paths) {
      if (p.exit && *p.exit == t) {
        mean += w * static_cast<double>(p.cycles);
        mass += w;
      }
    }
    if (mass <= 0.0) continue;
    mean /= mass;
    double centre = mean;  // where the durations are centred: the redrawn paths' mean when NOISE redraws
    if (redraws) {
      double m = 0.0, q = 0.0;
      for (const PathResult& p : redrawn) {
        if (p.exit && *p.exit == t) {
          m += w * static_cast<double>(p.cycles);
          q += w;
        }
      }
      if (q > 0.0) centre = m / q;
    }
    for (const PathResult& p : paths) {
      if (!p.exit || *p.exit != t) continue;
      const double shrink = redraw_shrink(p.cycles, persistence);
      // Whole cycles: the executive checks triggers once per cycle.
      values.push_back((centre + shrink * (static_cast<double>(p.cycles) - mean)) * cycle_s);
      ws.push_back(w);
    }
    a.exits.push_back({t, mass, from_weighted_points(values, ws, ctx.models->budget.max_components)});
  }

  // The mean path (sampled each second) for safety criteria.
  std::size_t longest = 0;
  for (const PathResult& p : paths) longest = std::max(longest, p.samples.size());
  for (std::size_t i = 0; i < longest; ++i) {
    PathSample s{};
    for (const PathResult& p : paths) {
      const PathSample& from = p.samples.empty() ? PathSample{0.0, start.x_m, start.y_m}
                                                  : p.samples[std::min(i, p.samples.size() - 1)];
      s.x_m += w * from.x_m;
      s.y_m += w * from.y_m;
    }
    s.offset_s = static_cast<double>(i) * 1.0;
    a.path.push_back(s);
  }
  return a;
}

/// Stop / Notify: zero command; the base brakes to rest (carried over if the
/// state is shorter than the braking, which the next state then continues).
StateAnalysis analyze_still(const StateContext& ctx, std::size_t state, const BaseState& start,
                            const ErrorState& error_start) {
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
  if (a.exits.empty() && !waits && !robot.is_final(state)) a.blocked = 1.0;
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
                            const ErrorState& error_start) {
  const mission::BehaviorKind kind = context.robot->states[state_index].kind();
  StateAnalysis a;
  if (kind == mission::BehaviorKind::go_to_guarded || kind == mission::BehaviorKind::spin) {
    a = analyze_motion(context, state_index, start, error_start);
    // A motion state that also listens for messages is not stuck just because
    // its own triggers never fire: the sequencer weighs the message instead.
    if (has_trigger_kind(*context.robot, state_index, mission::TriggerKind::notified) && a.exits.empty()) a.blocked = 0.0;
  } else {
    a = analyze_still(context, state_index, start, error_start);
  }
  return a;
}

}  // namespace p3at::verifier::engine
