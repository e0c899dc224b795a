#include "engine/path_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <variant>

#include "engine/body_contact.hpp"
#include "engine/moving_bodies.hpp"
#include "engine/sonar_model.hpp"
#include "p3at/executive/frames.hpp"
#include "p3at/executive/sonar.hpp"

namespace p3at::verifier::engine {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

exec::BehaviorConfig behavior_config(const mission::RobotSpec& robot, const Kinematics& k) {
  exec::BehaviorConfig c;
  c.max_speed_mps = robot.max_speed_mps;
  c.max_rot_radps = k.max_rot_vel_radps;
  c.rot_gain = k.rot_gain;
  c.robot_radius_m = k.robot_radius_m;
  return c;
}

}  // namespace

PathStepper::PathStepper(const StateContext& context, std::size_t state)
    : ctx_(context), state_(state), config_(behavior_config(*context.robot, context.model->kinematics)) {
  const mission::BehaviorParams& behavior = context.robot->states[state].behavior;
  go_ = std::get_if<mission::GoToGuardedParams>(&behavior);
  spin_ = std::get_if<mission::SpinParams>(&behavior);
  const Kinematics& k = context.model->kinematics;
  sample_every_ = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(1.0 / k.cycle_s)));
  max_range_m_ = context.models->environment.sonar_max_range_m;
  // How far from the robot's (true) centre an obstacle can still push it:
  // contact distance plus the sphere of influence, plus the sonar ring's
  // offset from the centre (a reading is the distance from the transducer),
  // plus a little for rounding.
  constexpr double kSonarOffsetM = 0.3;
  avoid_reach_m_ = go_ ? k.robot_radius_m + go_->safety_margin_m + go_->sphere_m + kSonarOffsetM + 0.05 : 0.0;
  // How far the rays need casting: a reading r puts its obstacle point at
  // least r minus the ring's offset from the robot's odometric centre, so one
  // beyond avoid_reach_m_ + 0.5 lies more than half a metre outside contact
  // distance plus sphere, where AVOID_OBSTACLES skips a point outright. It
  // may as well read "nothing seen": the command is the same to the bit.
  cast_m_ = avoid_reach_m_ + 0.5;
}

std::optional<std::size_t> PathStepper::fired(const Walker& w) const {
  if (w.cycles < 1) return std::nullopt;
  const mission::RobotSpec& robot = *ctx_.robot;
  // In file order: the executive's order.
  for (const std::size_t t : robot.states[state_].outgoing) {
    const mission::TriggerParams& trigger = robot.transitions[t].trigger;
    if (const auto* g = std::get_if<mission::AtGoalParams>(&trigger)) {
      if (std::hypot(g->goal.x_m - w.q.x_m, g->goal.y_m - w.q.y_m) <= g->radius_m) return t;
    } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
      if (w.turned_rad >= (h->angle_deg - h->offset_deg) * kDegToRad) return t;
    }
  }
  return std::nullopt;
}

double PathStepper::settle_phase(Walker& w, std::size_t transition, double* crossing_c, Eigen::Vector3d* step,
                                 double* crossing_sd) const {
  if (crossing_c) *crossing_c = -1.0;
  if (crossing_sd) *crossing_sd = 0.0;
  if (step) *step = Eigen::Vector3d(w.q.x_m - w.before.x_m, w.q.y_m - w.before.y_m, w.q.theta_rad - w.before.theta_rad);
  // The executive checks a trigger once per cycle, and where in that cycle a
  // real run crosses the threshold is as good as random: with the crossing a
  // fraction c into the last cycle (linear between the two checks), the check
  // that fires comes uniformly 0..1 cycle after it, on average c - 0.5 cycles
  // from the deterministic firing.
  const mission::TriggerParams& trigger = ctx_.robot->transitions[transition].trigger;
  double from = 0.0, to = 0.0, threshold = 0.0, progress_var = 0.0;
  if (const auto* g = std::get_if<mission::AtGoalParams>(&trigger)) {
    from = std::hypot(g->goal.x_m - w.before.x_m, g->goal.y_m - w.before.y_m);
    to = std::hypot(g->goal.x_m - w.q.x_m, g->goal.y_m - w.q.y_m);
    threshold = g->radius_m;
    progress_var = w.at_goal_jitter_var;
  } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
    from = -w.turned_before_rad;  // decreasing toward -threshold, like a distance
    to = -w.turned_rad;
    threshold = -(h->angle_deg - h->offset_deg) * kDegToRad;
    progress_var = w.turn_jitter_var;
  } else {
    return 0.0;
  }
  if (!(from > threshold) || !(from > to)) return 0.0;  // fired at once, or not by moving toward it
  const double c = std::clamp((from - threshold) / (from - to), 0.0, 1.0);
  if (crossing_c) *crossing_c = c;
  // The crossing time is off by N(0, progress_var) cycles (Walker::at_goal_jitter_var).
  if (crossing_sd) *crossing_sd = std::sqrt(std::max(progress_var, 0.0));
  const double phase = c - 0.5;
  w.q.x_m += phase * (w.q.x_m - w.before.x_m);
  w.q.y_m += phase * (w.q.y_m - w.before.y_m);
  w.q.theta_rad += phase * (w.q.theta_rad - w.before.theta_rad);
  return phase;
}

bool PathStepper::obstacle_within(const Walker& w, double x_m, double y_m, double reach_m) const {
  return any_within(ctx_.obstacles, x_m, y_m, reach_m) ||
         (ctx_.movers && ctx_.movers->within(w.cycles, x_m, y_m, reach_m));
}

bool PathStepper::delicate(const Walker& w) const {
  if (!go_) return false;
  if (std::hypot(go_->goal.x_m - w.q.x_m, go_->goal.y_m - w.q.y_m) <= go_->dropoff_m + 0.5) return true;
  return obstacle_within(w, w.q.x_m + w.error.mean(0), w.q.y_m + w.error.mean(1), avoid_reach_m_ + 0.5);
}

void PathStepper::step(Walker& w, const exec::Vec2<double>& noise_direction) const {
  const Kinematics& k = ctx_.model->kinematics;
  double trans = 0.0, rot = 0.0;
  // Whether a wall or a still body is within AVOID_OBSTACLES' reach: beyond
  // it, neither the sonar's readings nor the body's contact can matter.
  bool obstacles_near = false;
  if (go_) {
    // The sonar sees the world from the true pose; the executive places what
    // it sees around its odometric pose.
    const double tx = w.q.x_m + w.error.mean(0), ty = w.q.y_m + w.error.mean(1);
    const double tth = w.q.theta_rad + w.error.mean(2);
    const exec::Pose<double> pose{w.q.x_m, w.q.y_m, w.q.theta_rad};
    exec::SonarObstacles<double> obstacles;
    // AVOID_OBSTACLES ignores anything beyond its reach, so when nothing is
    // that close the readings cannot matter and need not be cast (exact).
    // Driving teammates are where their predicted paths put them at this
    // cycle (engine/moving_bodies.hpp); for the same reason only the bodies
    // within reach are added to the segments the rays are cast against.
    const bool mates_near = ctx_.movers && ctx_.movers->within(w.cycles, tx, ty, avoid_reach_m_);
    obstacles_near = any_within(ctx_.obstacles, tx, ty, avoid_reach_m_);
    if (mates_near || obstacles_near) {
      std::vector<Segment> with_mates;
      if (mates_near) {
        with_mates = ctx_.obstacles;
        ctx_.movers->append_within(w.cycles, tx, ty, avoid_reach_m_, with_mates);
      }
      const auto ranges = sonar_ranges(mates_near ? with_mates : ctx_.obstacles, tx, ty, tth, max_range_m_, cast_m_);
      obstacles = exec::sonar_obstacles(std::span<const double, exec::kP3atSonarCount>(ranges), pose, max_range_m_);
    }
    const exec::Velocity<double> v = exec::go_to_guarded(*go_, pose, obstacles.view(), noise_direction, config_);
    trans = v.trans_mps;
    rot = v.rot_radps;
  } else if (spin_) {
    rot = exec::spin_command(*spin_, config_).rot_radps;
  }
  w.before = w.q;
  w.turned_before_rad = w.turned_rad;
  // The body stalls against a wall where every run would (body_contact.hpp;
  // StateContext::walls); only checked where a wall is that close. The
  // avoidance's reach is usually beyond contact's (a robot radius of 0.4 m
  // and more against a half-diagonal of 0.40 m plus a cycle's travel), so
  // its check above mostly answers for both.
  const double reach = contact_reach_m(std::max(config_.max_speed_mps, std::abs(w.q.trans_mps)), k.max_rot_vel_radps,
                                       k.cycle_s);
  const bool contact = (obstacles_near || reach > avoid_reach_m_) &&
                       any_within(ctx_.walls, w.q.x_m + w.error.mean(0), w.q.y_m + w.error.mean(1), reach);
  const CycleIncrement inc = contact ? step_cycle_against(w.q, trans, rot, k, ctx_.walls, w.error.mean.data())
                                     : step_cycle(w.q, trans, rot, k);
  propagate(w.error, inc, ctx_.model->motion);
  if (go_ && std::abs(inc.ds_m) > 0.0) {
    // The fraction of the step that closes on the goal (a step across the
    // bearing leaves the believed distance, and so the crossing, alone).
    const double gx = go_->goal.x_m - w.before.x_m, gy = go_->goal.y_m - w.before.y_m;
    const double range = std::hypot(gx, gy);
    const double dx = w.q.x_m - w.before.x_m, dy = w.q.y_m - w.before.y_m;
    const double step = std::hypot(dx, dy);
    if (range > 0.0 && step > 0.0) {
      const double radial = (dx * gx + dy * gy) / (range * step);
      if (radial > 0.0) w.at_goal_jitter_var += ctx_.model->motion.trans_rel_var * radial * radial;
    }
  }
  if (inc.dtheta_rad != 0.0) w.turn_jitter_var += ctx_.model->motion.rot_rel_var;
  w.turned_rad += std::abs(exec::wrap_angle_rad(inc.dtheta_rad));
  ++w.cycles;
}

bool PathStepper::static_surroundings() const { return !ctx_.movers || ctx_.movers->empty(); }

}  // namespace p3at::verifier::engine
