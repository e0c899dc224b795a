#include "engine/sequencer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <tuple>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "engine/error_state.hpp"
#include "engine/interruption.hpp"
#include "engine/moved_start.hpp"
#include "engine/moving_bodies.hpp"
#include "engine/race.hpp"
#include "engine/separations.hpp"
#include "p3at/verifier/separation.hpp"
#include "engine/state_analysis.hpp"

namespace p3at::verifier::engine {
namespace {

// Orderings less likely than this are not worth a branch.
constexpr double kNegligible = 1e-9;
// Bins of the interruption time when a message takes a robot out of a motion
// state (engine/interruption.hpp): each a branch until the robot's next event.
constexpr std::size_t kInterruptionBins = 12;

Mixture1 negated(const Mixture1& x) {
  Mixture1 out = x;
  for (Component1& c : out.components) c.mean = -c.mean;
  return out;
}

/// The weighted union of two mixtures (for merging branches).
Mixture1 blend(const Mixture1& a, double wa, const Mixture1& b, double wb, std::size_t k) {
  Mixture1 out;
  for (const Component1& c : a.components) out.components.push_back({c.weight * wa, c.mean, c.var});
  for (const Component1& c : b.components) out.components.push_back({c.weight * wb, c.mean, c.var});
  out.normalise();
  reduce(out, k);
  return out;
}

/// The range outside which a mixture has (practically) no mass: every
/// component's mean -/+ 8 standard deviations (a tail below 1e-15).
std::pair<double, double> plausible_span(const Mixture1& x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Component1& c : x.components) {
    const double reach = 8.0 * std::sqrt(std::max(c.var, 0.0));
    lo = std::min(lo, c.mean - reach);
    hi = std::max(hi, c.mean + reach);
  }
  return {lo, hi};
}

/// The variance an event's time took out of a pending residual that was
/// surely later (remaining_after): (the event's sequence number, the variance).
/// The residual's mixture keeps Var X - Var Y so that the clock plus the
/// residual has Var X; but compared with something that did not share that
/// event (a message sent later, a robot that entered a state after it), the
/// residual's spread is Var X + Var Y. Every such comparison adds back twice
/// the variance of the events in either side's list (see comparison_var).
struct Hidden {
  std::size_t event = 0;
  double var = 0.0;
};
using HiddenList = std::vector<Hidden>;

/// 2 x the variance over the union of two hidden lists (by event).
double comparison_var(const HiddenList& a, const HiddenList& b) {
  double sum = 0.0;
  for (const Hidden& h : a) sum += h.var;
  for (const Hidden& h : b) {
    const bool shared = std::any_of(a.begin(), a.end(), [&](const Hidden& g) { return g.event == h.event; });
    if (!shared) sum += h.var;
  }
  return 2.0 * sum;
}

/// x with every component's variance grown by `extra`.
Mixture1 widened(const Mixture1& x, double extra) {
  if (!(extra > 0.0)) return x;
  Mixture1 out = x;
  for (Component1& c : out.components) c.var += extra;
  return out;
}

/// X - Y given X > Y, for independent X, Y: what is left of a pending
/// duration after another event happened first. When X is surely later, the
/// variance taken out is appended to `hidden` under `event`.
Mixture1 remaining_after(const Mixture1& x, const Mixture1& y, std::size_t k, HiddenList* hidden = nullptr,
                         std::size_t event = 0) {
  const auto [x_lo, x_hi] = plausible_span(x);
  const auto [y_lo, y_hi] = plausible_span(y);
  (void)x_hi;
  (void)y_lo;
  if (x_lo > y_hi) {
    // X is surely later: no conditioning, and Y enters only through its mean
    // and variance (exact for the difference's first two moments), which
    // costs one pass over X instead of a pairwise sum and a reduction.
    const double y_mean = y.mean(), y_var = y.variance();
    Mixture1 left = x;
    double taken = 0.0;  // the variance actually taken out (components cannot go below 0)
    for (Component1& c : left.components) {
      c.mean -= y_mean;
      const double v = std::max(c.var - y_var, 0.0);
      taken += c.weight * (c.var - v);
      c.var = v;
    }
    // What the components could not give (point masses: a leg's NOISE paths)
    // comes out of the spread between them, pulling their means toward the
    // mixture's mean, so that the clock plus the residual keeps Var X.
    const double rest = y_var - taken;
    if (rest > 0.0) {
      const double m = left.mean();
      double between = 0.0;
      for (const Component1& c : left.components) between += c.weight * (c.mean - m) * (c.mean - m);
      if (between > 0.0) {
        const double shrink = std::sqrt(std::max(0.0, between - rest) / between);
        for (Component1& c : left.components) c.mean = m + shrink * (c.mean - m);
        taken += between * (1.0 - shrink * shrink);
      }
    }
    if (hidden != nullptr && taken > 0.0) hidden->push_back({event, taken});
    return left;
  }
  const Mixture1 diff = sum(x, negated(y), k);
  double p = 0.0;
  Mixture1 left = conditioned_greater(diff, Mixture1::point(0.0), k, p);
  if (left.components.empty() || !(p > 0.0)) return Mixture1::point(0.0);
  return left;
}

/// The robots whose events decided a time (a bit per robot; a robot beyond
/// the 64th counts as every robot, which only ever makes times dependent).
/// Two times of disjoint lineages are independent: their absolute values can
/// be compared as independent random variables, exactly, where residuals
/// relative to a clock that one of them built cannot (a patrol's laps against
/// a teammate's long leg: the teammate's residual after each lap keeps the
/// lap's spread, or loses it, but never as an independent time would).
using Lineage = std::uint64_t;
Lineage lineage_of(std::size_t robot) { return robot < 64 ? (Lineage{1} << robot) : ~Lineage{0}; }
bool independent(Lineage a, Lineage b) { return (a & b) == 0; }

/// A Spin's odometric turn applied to a pose predicted ahead (legs_ahead):
/// the heading turns by `turn_rad` and the error grows as the wheels make it
/// (rot_scale, the turn's own forward motion, the rotation noise), in steps of
/// at most a degree so a turn's forward motion follows the heading round.
/// Before, only the heading turned: generated gen_6081's robot5 spins 360
/// degrees by robot1's goal on wheels that turn it 11 degrees short, and its
/// predicted next leg stood 0.6 m nearer that goal than its real one, holding
/// robot1 off its AtGoal circle on 9 % of its paths (joint error 0.966 against
/// 1,000 runs; 0.039 now).
void spin_in_place(BaseState& base, ErrorState& error, double turn_rad, const MotionError& motion) {
  constexpr double kMaxStepRad = 3.14159265358979323846 / 180.0;
  const auto steps = static_cast<std::size_t>(std::ceil(std::abs(turn_rad) / kMaxStepRad));
  if (steps == 0) return;
  const double step = turn_rad / static_cast<double>(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    CycleIncrement inc;
    inc.dtheta_rad = step;
    inc.mid_theta_rad = base.theta_rad + step / 2.0;
    propagate(error, inc, motion);
    base.theta_rad += step;
  }
}

struct Pending {
  std::size_t transition = 0;
  Mixture1 residual;  ///< seconds from the branch clock until it fires
  HiddenList hidden;  ///< variance taken out by earlier events (remaining_after)
  /// The mission time at which it fires (conditioned on the events before it
  /// that were independent of it), and whose events decided that time.
  std::optional<Mixture1> absolute;
  Lineage lineage = 0;
  /// An event independent of this time (disjoint lineages) has advanced the
  /// clock since the residual was set: the residual is now the difference of
  /// two independent times, and the clock plus the residual would count that
  /// event's spread twice (the residual cannot give it back when the event is
  /// the wider of the two). Such a time fires at `absolute`.
  bool detached = false;
};

struct Track {
  std::size_t state = 0;
  /// Stuck on its path in a state that listens for a message: standing where
  /// the stuck paths stopped (analysis.blocked_x_m, _y_m) until it comes.
  bool stuck_waiting = false;
  BaseState base;                 ///< odometry at the current state's start
  ErrorState error;
  /// The error's spread between NOISE paths kept apart (engine/error_mixture.hpp;
  /// `error.cov` is still the total).
  ErrorMixture error_mix;
  /// The part of error_mix from before the last GoToGuarded (that leg's own
  /// paths' errors are in spread_points, added per path to where it ended),
  /// and the covariance of that leg's paths' errors (in error.cov, shown by
  /// spread_points); `spread_points_within` is what the points average away.
  ErrorMixture error_mix_before_leg;
  Eigen::Matrix2d leg_paths_cov = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d spread_points_within = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  std::vector<Eigen::Vector2d> spread_points;  ///< the points `spread` is the covariance of (may be empty)
  /// Each spread point's probability (StateAnalysis::end_weights); empty
  /// when they are equally likely.
  std::vector<double> spread_weights;
  /// How much later than their mean each point's paths fired (seconds, the
  /// same order; StateAnalysis::end_delays); empty when not known.
  std::vector<double> spread_delays;
  /// The last leg's spread_points once each path has braked to rest on its
  /// own, and what they average away (StateAnalysis::rest_offsets): they
  /// replace spread_points on entering a state that stops the robot.
  std::vector<Eigen::Vector2d> rest_points;
  std::vector<double> rest_weights;
  Eigen::Matrix2d rest_points_within = Eigen::Matrix2d::Zero();
  std::vector<double> rest_delays;
  StateAnalysis analysis;         ///< of the current state
  /// Where the previous state left the robot (equally likely points around
  /// `base`; state_analysis.hpp's StartPoint): the current state's paths
  /// start from them. Empty: from `base`.
  std::vector<StartPoint> start_points;
  std::vector<Pending> pending;
  bool final = false;
  Mixture1 finish;
  std::vector<std::string> trace;
  // The current state's entry, for an interruption (engine/interruption.hpp):
  // the clock then, the events before it, and the time since (the sum of the
  // clock's increments; `since_hidden` is what comparison_var would add back
  // for the increments' hidden variance from events before the entry).
  Mixture1 entry_clock = Mixture1::point(0.0);
  Lineage entry_lineage = 0;
  Lineage lineage = 0;  ///< whose events decided when the robot entered its current state
  std::size_t entry_events = 0;
  Mixture1 since_entry = Mixture1::point(0.0);
  double since_hidden = 0.0;
  /// The bin of the interruption that took it out of its last motion state
  /// (0: none); part of the branch's configuration until its next event, so
  /// the bins are not merged back into one pose.
  std::size_t interruption_bin = 0;
  /// Entries per state in this branch: a loop's laps (the budget cuts them off).
  std::vector<std::size_t> visits;
  /// The motion within that bin, a position spread on top of `spread`; and
  /// the spread between the starts of branches merged after the current
  /// state's analysis was made (merge_into), which the analysis's paths do
  /// not carry.
  Eigen::Matrix2d extra_cov = Eigen::Matrix2d::Zero();
  /// How far `base` has moved from where the current state's analysis began:
  /// branches that entered the state from different places were merged and
  /// one analysis goes on for all (engine/moved_start.hpp). Zero on entry.
  Eigen::Vector2d moved_start = Eigen::Vector2d::Zero();
  /// Where it is predicted to be over mission time (separation criteria).
  Timeline timeline;

  Eigen::Vector2d true_mean() const { return {base.x_m + error.mean(0), base.y_m + error.mean(1)}; }
  Gaussian2 true_position() const {
    Gaussian2 g;
    g.mean = true_mean();
    g.cov = spread + extra_cov + error.cov.topLeftCorner<2, 2>();
    return g;
  }
};

struct BranchState {
  double weight = 1.0;
  Mixture1 clock = Mixture1::point(0.0);
  std::vector<Track> robots;
  std::vector<std::optional<Mixture1>> delivery;  ///< per message: residual until delivered; nullopt = not sent
  std::vector<std::optional<Mixture1>> delivery_at;  ///< per message: the mission time it is delivered
  std::vector<Lineage> delivery_lineage;             ///< per message: whose events decided that time
  Lineage clock_lineage = 0;                          ///< whose events decided the clock
  std::vector<std::size_t> event_robots;
  /// The share of the weight whose places were merged over the branch budget
  /// (merge_and_prune); SystemOutcome::budget_merged_mass when it finishes.
  double coarse = 0.0;
};

class Sequencer {
 public:
  Sequencer(const mission::Mission& mission, const Models& models) : mission_(mission), models_(models) {
    for (const Wall& w : models.environment.walls) walls_.push_back({w.x0_m, w.y0_m, w.x1_m, w.y1_m});
    for (const mission::RobotSpec& r : mission.robots) robot_models_.push_back(models.find_robot(r.name));
  }

  SystemOutcome run(const TeamSnapshot* from) {
    evaluate(from ? start_from(*from) : start());
    return std::move(outcome_);
  }

 private:
  std::size_t k() const { return models_.budget.max_components; }
  std::size_t max_visits() const { return std::max<std::size_t>(1, models_.budget.max_events / 100); }
  double cycle_s(std::size_t robot) const { return robot_models_[robot]->kinematics.cycle_s; }

  /// The Def. 10 loop: one event per branch per step until every branch has
  /// finished; what is still active after Budget::max_events per robot is a
  /// loop that never ends, counted as blocked.
  void evaluate(std::vector<BranchState> active) {
    const std::size_t max_steps = models_.budget.max_events * std::max<std::size_t>(1, mission_.robots.size());
    for (std::size_t step = 0; !active.empty() && step < max_steps; ++step) {
      if (outcome_.work_cycles > models_.budget.max_work_cycles) {
        // Out of time for the robot's pre-launch check: what is left counts as failure.
        for (const BranchState& b : active) outcome_.work_cutoff_mass += b.weight;
        active.clear();
        break;
      }
      std::vector<BranchState> next;
      for (BranchState& b : active) advance(std::move(b), next);
      active = merge_and_prune(std::move(next));
    }
    for (const BranchState& b : active) {
      outcome_.blocked_mass += b.weight;
      note_unfinished(b, "loop");
    }
  }

  std::vector<BranchState> start() {
    BranchState b;
    b.delivery.assign(mission_.messages.size(), std::nullopt);
    b.delivery_at.assign(mission_.messages.size(), std::nullopt);
    b.delivery_lineage.assign(mission_.messages.size(), 0);
    for (const mission::RobotSpec& r : mission_.robots) {
      Track t;
      t.lineage = lineage_of(b.robots.size());
      constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
      t.base = BaseState{r.start.x_m, r.start.y_m, r.start.theta_deg * kDegToRad, 0.0, 0.0};
      // The state it will enter at launch: a robot entered earlier (file
      // order) sees it there (obstacles_near, moving_teammates).
      t.state = r.initial;
      b.robots.push_back(std::move(t));
    }
    std::vector<BranchState> branches{std::move(b)};
    for (std::size_t i = 0; i < mission_.robots.size(); ++i) {
      entering_ = i;  // robots after i have not entered a state yet
      std::vector<BranchState> entered;
      for (BranchState& br : branches) enter(std::move(br), i, mission_.robots[i].initial, entered);
      branches = std::move(entered);
    }
    entering_ = kNone;
    return branches;
  }

  std::vector<BranchState> start_from(const TeamSnapshot& snap) {
    // The error accumulated so far is the nominal prediction's at the entry of
    // each robot's current state (the robots cannot observe it).
    record_entries_ = true;
    evaluate(start());
    record_entries_ = false;
    outcome_ = SystemOutcome{};
    legs_seen_.clear();
    leg_entries_of_.clear();  // indices into the outcome just reset
    look_ahead_cache_.clear();  // its cycles count toward this evaluation's budget again

    BranchState b;
    b.clock = Mixture1::point(snap.elapsed_s);
    b.delivery.assign(mission_.messages.size(), std::nullopt);
    b.delivery_at.assign(mission_.messages.size(), std::nullopt);
    b.delivery_lineage.assign(mission_.messages.size(), 0);
    for (std::size_t m = 0; m < mission_.messages.size(); ++m) {
      const bool sent = m < snap.messages_sent.size() && snap.messages_sent[m];
      const bool received = m < snap.messages_received.size() && snap.messages_received[m];
      if (received) b.delivery[m] = Mixture1::point(0.0);
      else if (sent) b.delivery[m] = delay_in_cycles(models_.comm.delivery_s, cycle_s(mission_.messages[m].from), k());
      if (b.delivery[m]) {
        b.delivery_at[m] = sum(b.clock, *b.delivery[m], k());
        b.delivery_lineage[m] = lineage_of(mission_.messages[m].from);
      }
    }
    for (std::size_t i = 0; i < mission_.robots.size(); ++i) {
      const RobotSnapshot& s = snap.robots.at(i);
      Track t;
      t.lineage = lineage_of(i);
      t.base = BaseState{s.x_m, s.y_m, s.theta_rad, 0.0, 0.0};
      const auto it = entry_errors_.find({i, s.state});
      if (it != entry_errors_.end()) t.error = it->second;
      t.state = s.state;
      if (s.finished) {
        t.final = true;
        t.finish = Mixture1::point(s.entered_s);
      }
      b.robots.push_back(std::move(t));
    }
    std::vector<BranchState> branches{std::move(b)};
    for (std::size_t i = 0; i < mission_.robots.size(); ++i) {
      if (snap.robots[i].finished) continue;
      entering_ = mission_.robots.size();  // every robot's state is known from the snapshot
      std::vector<BranchState> entered;
      for (BranchState& br : branches) enter(std::move(br), i, snap.robots[i].state, entered, /*trace=*/false);
      branches = std::move(entered);
    }
    entering_ = kNone;
    return branches;
  }


  /// Robot i enters `state` at the branch clock. May split the branch by
  /// which self-timed exit its path takes; splits off blocked mass.
  void enter(BranchState b, std::size_t i, std::size_t state, std::vector<BranchState>& out, bool trace = true) {
    const mission::RobotSpec& spec = mission_.robots[i];
    Track& track = b.robots[i];
    track.state = state;
    track.pending.clear();
    track.stuck_waiting = false;
    // A loop (a back-edge in the FSA) is the paper's tail recursion unrolled
    // one lap per entry; laps beyond the budget are cut off, their mass
    // reported and counted as failure.
    if (track.visits.size() < spec.states.size()) track.visits.resize(spec.states.size(), 0);
    if (++track.visits[state] > max_visits()) {
      outcome_.loop_cutoff_mass += b.weight;
      return;
    }
    track.entry_clock = b.clock;
    track.entry_lineage = b.clock_lineage;
    track.entry_events = b.event_robots.size();
    track.since_entry = Mixture1::point(0.0);
    track.since_hidden = 0.0;
    if (trace) track.trace.push_back(spec.states[state].name);
    if (!track.rest_points.empty() && brakes_to_rest(spec, state, robot_models_[i]->kinematics)) {
      // The points are relative to where the mean path comes to rest; their
      // mean is how much farther the paths run out on average (the braking
      // distance grows with the square of the speed). The base takes that
      // along, so that the points stay centred on it and the moment-matched
      // final position is the mixture's.
      Eigen::Vector2d shift = Eigen::Vector2d::Zero();
      for (std::size_t j = 0; j < track.rest_points.size(); ++j) {
        shift += track.rest_weights.empty() ? Eigen::Vector2d(track.rest_points[j] / static_cast<double>(track.rest_points.size()))
                                            : Eigen::Vector2d(track.rest_weights[j] * track.rest_points[j]);
      }
      for (Eigen::Vector2d& p : track.rest_points) p -= shift;
      track.base.x_m += shift.x();
      track.base.y_m += shift.y();
      track.spread_points = std::move(track.rest_points);
      track.spread_weights = std::move(track.rest_weights);
      track.spread_points_within = track.rest_points_within;
      track.spread_delays = std::move(track.rest_delays);
    }
    track.rest_points.clear();
    track.rest_weights.clear();
    track.rest_delays.clear();
    if (record_entries_) entry_errors_.emplace(std::make_pair(i, state), track.error);

    // Notify: the message goes out on entry.
    if (const auto* notify = std::get_if<mission::NotifyParams>(&spec.states[state].behavior)) {
      if (const auto m = mission_.find_message(notify->message)) {
        b.delivery[*m] = delay_in_cycles(models_.comm.delivery_s, cycle_s(i), k());
        b.delivery_at[*m] = sum(b.clock, *b.delivery[*m], k());
        b.delivery_lineage[*m] = track.lineage;
        release_waiters(b, *m);
      }
    }
    if (spec.is_final(state)) {
      track.final = true;
      track.finish = b.clock;  // the completion time: entering the final state
      // The final position is where the robot comes to rest: the executive
      // stops the base here and it brakes from the speed it fired at (v^2 /
      // (2 decel): 7.5 cm at 0.3 m/s on a P3-AT). The run-out moves the odometric base and
      // carries the error along it as a state change does in fire(); the
      // spread points are relative to the base and ride with it.
      StateContext ctx;
      ctx.robot = &spec;
      ctx.model = robot_models_[i];
      ctx.models = &models_;
      track.analysis = analyze_final(ctx, state, track.base, track.error);
      track.moved_start.setZero();
      outcome_.work_cycles += track.analysis.cycles_simulated;
      const double dx = track.analysis.end.x_m - track.base.x_m, dy = track.analysis.end.y_m - track.base.y_m;
      transport(track.error_mix, dx, dy);
      transport(track.error_mix_before_leg, dx, dy);
      track.base = track.analysis.end;
      track.error = track.analysis.error;
      out.push_back(std::move(b));
      return;
    }

    StateContext ctx;
    ctx.robot = &spec;
    ctx.model = robot_models_[i];
    ctx.models = &models_;
    ctx.walls = near_way(walls_, b, i, state);
    ctx.obstacles = obstacles_near(b, i, state, ctx.walls);
    ctx.movers = moving_teammates(b, i, state);
    Eigen::Vector2d reused_from_elsewhere = Eigen::Vector2d::Zero();
    bool reused = false;
    track.analysis = cached_analysis(ctx, i, state, track, reused, reused_from_elsewhere);
    track.moved_start = reused_from_elsewhere;
    if (reused) {
      b.coarse = 1.0;
      outcome_.work_pressure_merged = true;
      note_budget_merge_of(i, state, true);
    }
    outcome_.subsystems += 1;
    note_path(b, i);

    // Exits driven by messages already on their way.
    for (const std::size_t t : spec.states[state].outgoing) {
      const auto* n = std::get_if<mission::NotifiedParams>(&spec.transitions[t].trigger);
      if (n == nullptr) continue;
      const auto m = mission_.find_message(n->message);
      if (m && b.delivery[*m]) {
        // Seen at the earliest one cycle after the entry: already delivered,
        // the time is the robot's own; still on its way, the later of the two.
        const Mixture1 seen = shifted(b.clock, cycle_s(i));
        const bool delivered = plausible_span(*b.delivery[*m]).second <= 0.0;
        Pending p{t, maximum(*b.delivery[*m], cycle_s(i)), {}, std::nullopt, track.lineage};
        if (delivered) {
          p.absolute = seen;
        } else if (b.delivery_at[*m]) {
          p.absolute = maximum(*b.delivery_at[*m], seen, k());
          p.lineage |= b.delivery_lineage[*m];
        }
        track.pending.push_back(std::move(p));
      }
    }
    const StateAnalysis& a = track.analysis;
    note_concurrent_legs(b, i, state);
    note_leg_entry(b.robots[i], i, state);
    // A motion state that listens for a message (it has a trajectory) is not
    // over for a path that gets stuck on the way (pinned by a wall's
    // avoidance, held off its goal by NOISE): the robot stands where that
    // path stopped until the message takes it on, as a robot in a Stop
    // waits. If no message ever comes, the branch ends blocked like any
    // wait nobody answers. gen_5062's patrol (robot2 alone pinned in 99 % of
    // the runs, the team's relief reaching it first in all of them) was
    // counted blocked with P 0.998 where every run succeeds.
    if (a.trajectory) {
      const bool no_exits = a.exits.empty();
      const double stuck_mass = no_exits ? 1.0 : a.blocked;
      if (stuck_mass > kNegligible) {
        BranchState waiting = no_exits ? std::move(b) : b;
        waiting.weight *= stuck_mass;
        Track& w = waiting.robots[i];
        if (w.analysis.stuck_trajectory) w.analysis.trajectory = w.analysis.stuck_trajectory;
        w.analysis.exits.clear();
        w.stuck_waiting = true;
        out.push_back(std::move(waiting));
      }
      if (no_exits) return;
    } else if (a.blocked > kNegligible) {
      outcome_.blocked_mass += b.weight * a.blocked;
      note_blocked(i, state, a.blocked_x_m + track.error.mean(0), a.blocked_y_m + track.error.mean(1), "stuck",
                   b.weight * a.blocked);
    }
    if (a.exits.empty()) {
      if (a.blocked < 1.0 - kNegligible) {
        b.weight *= (1.0 - a.blocked);
        out.push_back(std::move(b));
      }
      return;
    }
    for (const TimedExit& e : a.exits) {
      BranchState child = b;
      child.weight = b.weight * e.probability;
      child.robots[i].pending.push_back(
          {e.transition, e.duration_s, {}, sum(b.clock, e.duration_s, k()), child.robots[i].lineage});
      out.push_back(std::move(child));
    }
  }

  /// analyze_state() is a pure function of its inputs, and branches that
  /// differ only in other robots' orderings enter a robot's state with the
  /// same ones: the analysis is made once per distinct input (bit for bit, so
  /// the answer is what recomputing would give) and the work budget counts
  /// only the cycles really simulated. On generated 6-robot missions the same
  /// state was otherwise analysed once per branch (up to 32 times).
  ///
  /// Past kWorkPressureAt of the work budget, an entry with no analysis of its
  /// own takes the analysis of the nearest place this robot entered the state
  /// from (`reused`; `moved` is how far its start is from that one's, carried
  /// as a merged start is: engine/moved_start.hpp). A leg entered from many
  /// places is analysed once per place, and that count is what runs the
  /// budget out: gen_7610's and gen_7577's robot2, relieved from a patrol, had
  /// its next leg analysed 118 and 87 times (124 M cycles each), the rest of
  /// the mass then cut off and counted as failure (P 0 where the runs
  /// finish). The picture is coarser (the entry's heading, error and
  /// teammates are the other place's), and the gate does not vouch for it
  /// (`places-merged-over-budget`).
  StateAnalysis cached_analysis(const StateContext& ctx, std::size_t i, std::size_t state, const Track& track,
                                bool& reused, Eigen::Vector2d& moved) {
    std::string key;
    const auto put = [&key](double v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); };
    put(static_cast<double>(i));
    put(static_cast<double>(state));
    for (const double v : {track.base.x_m, track.base.y_m, track.base.theta_rad, track.base.trans_mps, track.base.rot_radps}) put(v);
    for (Eigen::Index r = 0; r < 3; ++r) {
      put(track.error.mean(r));
      for (Eigen::Index c = 0; c < 3; ++c) put(track.error.cov(r, c));
    }
    for (const StartPoint& p : track.start_points) {
      for (const double v : {p.q.x_m, p.q.y_m, p.q.theta_rad, p.q.trans_mps, p.q.rot_radps}) put(v);
      for (Eigen::Index r = 0; r < 3; ++r) put(p.error_offset(r));
    }
    key.push_back('|');
    for (const Segment& g : ctx.obstacles) {
      for (const double v : {g.x0, g.y0, g.x1, g.y1}) put(v);
    }
    // Moving teammates are a pose per cycle each: two independent 64-bit
    // hashes of them rather than their bytes (a key of up to tens of
    // kilobytes per entry), so a wrong hit needs a 128-bit collision.
    if (ctx.movers && !ctx.movers->empty()) {
      key.push_back('|');
      const auto [h1, h2] = ctx.movers->fingerprint();
      key.append(reinterpret_cast<const char*>(&h1), sizeof h1);
      key.append(reinterpret_cast<const char*>(&h2), sizeof h2);
    }
    const auto it = analysis_cache_.find(key);
    if (it != analysis_cache_.end()) return it->second;
    std::vector<MadeAnalysis>& made = analyses_made_[{i, state}];
    const double spent = static_cast<double>(outcome_.work_cycles) /
                         static_cast<double>(std::max<std::size_t>(1, models_.budget.max_work_cycles));
    if (spent > kWorkPressureAt && !made.empty()) {
      const auto apart = [&](const MadeAnalysis& m) {
        const double turn = std::remainder(track.base.theta_rad - m.start.theta_rad, 2.0 * 3.14159265358979323846);
        return std::hypot(track.base.x_m - m.start.x_m, track.base.y_m - m.start.y_m) + kHeadingMetresPerRad * std::abs(turn);
      };
      const auto nearest = std::min_element(made.begin(), made.end(),
                                            [&](const MadeAnalysis& x, const MadeAnalysis& y) { return apart(x) < apart(y); });
      reused = true;
      moved = Eigen::Vector2d(track.base.x_m - nearest->start.x_m, track.base.y_m - nearest->start.y_m);
      return nearest->analysis->second;
    }
    StateAnalysis a = analyze_state(ctx, state, track.base, track.error, track.start_points);
    outcome_.work_cycles += a.cycles_simulated;
    // Bounded (the first entries stay: deterministic); an analysis holds a
    // trajectory for interruptible states, so the cache is kept modest.
    if (analysis_cache_.size() < kMaxCachedAnalyses) made.push_back({track.base, analysis_cache_.emplace(std::move(key), a).first});
    return a;
  }

  /// Of `all`, the segments within sonar range of robot i's way in `state`
  /// (from where it is to its goal).
  std::vector<Segment> near_way(const std::vector<Segment>& all, const BranchState& b, std::size_t i,
                                std::size_t state) const {
    const Track& me = b.robots[i];
    double gx = me.base.x_m, gy = me.base.y_m;
    if (const auto* go = std::get_if<mission::GoToGuardedParams>(&mission_.robots[i].states[state].behavior)) {
      gx = go->goal.x_m;
      gy = go->goal.y_m;
    }
    const Eigen::Vector2d from = me.true_mean();
    return segments_near(all, from.x(), from.y(), gx, gy, models_.environment.sonar_max_range_m + 1.0);
  }

  /// The walls near robot i's way (`walls_near`, near_way of walls_) and
  /// after them the bodies of the teammates that hold still there.
  std::vector<Segment> obstacles_near(const BranchState& b, std::size_t i, std::size_t state,
                                      const std::vector<Segment>& walls_near) const {
    std::vector<Segment> bodies;
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      if (j == i) continue;
      // A teammate driving a GoToGuarded leg is not where its leg began for
      // long: pinning its body there would block a robot headed for the spot
      // it just left (a hand-over at a waypoint) for the whole state, nor is
      // one that holds still only until it drives off by itself (a Notify's
      // acknowledgement, a Spin's turn). Only teammates that hold still for
      // good as far as their own timing goes (finished, or waiting for a
      // message) are fixed obstacles; the others are bodies that move with
      // time (moving_teammates).
      if (!b.robots[j].final &&
          std::holds_alternative<mission::GoToGuardedParams>(mission_.robots[j].states[b.robots[j].state].behavior)) {
        continue;
      }
      if (drives_off_in(b, j)) continue;
      const Eigen::Vector2d p = b.robots[j].true_mean();
      const auto body = body_segments(p.x(), p.y(), b.robots[j].base.theta_rad + b.robots[j].error.mean(2));
      bodies.insert(bodies.end(), body.begin(), body.end());
    }
    // near_way filters segment by segment, in order: the walls' part is walls_near.
    std::vector<Segment> all = walls_near;
    const std::vector<Segment> bodies_near = near_way(bodies, b, i, state);
    all.insert(all.end(), bodies_near.begin(), bodies_near.end());
    return all;
  }

  /// The teammates driving a GoToGuarded leg when robot i enters `state`
  /// (a GoToGuarded; nothing else steers around obstacles), each as a body
  /// following its predicted mean true path over i's cycles, standing where
  /// its leg ends while it holds still after, and on along its next leg when
  /// the states in between lead there by their own triggers (predicted ahead
  /// from where the current leg ends: look_ahead) (engine/moving_bodies.hpp).
  /// One-way: each teammate's path was predicted without robot i. Null when
  /// none comes within sonar range of i's way (as obstacles_near filters).
  std::shared_ptr<const MovingBodies> moving_teammates(const BranchState& b, std::size_t i, std::size_t state) {
    const auto* go = std::get_if<mission::GoToGuardedParams>(&mission_.robots[i].states[state].behavior);
    if (go == nullptr) return nullptr;
    const Eigen::Vector2d from = b.robots[i].true_mean();
    const double reach = models_.environment.sonar_max_range_m + 1.0;
    auto bodies = std::make_shared<MovingBodies>();
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      const Track& tj = b.robots[j];
      const mission::RobotSpec& spec = mission_.robots[j];
      if (j == i || tj.final) continue;
      if (!std::holds_alternative<mission::GoToGuardedParams>(spec.states[tj.state].behavior)) {
        // Holding still now: a fixed obstacle (obstacles_near) unless it
        // drives off by its own triggers, then a body standing here until then.
        if (std::optional<MovingBody> body = still_then_off(b, j, i)) {
          if (passes_near(*body, from.x(), from.y(), go->goal.x_m, go->goal.y_m, reach)) bodies->add(std::move(*body));
        }
        continue;
      }
      const std::vector<TeammateLeg> legs = driving_legs(b, j);
      if (legs.empty()) continue;
      MovingBody body = follow_legs(legs, cycle_s(i));
      if (passes_near(body, from.x(), from.y(), go->goal.x_m, go->goal.y_m, reach)) bodies->add(std::move(body));
    }
    if (bodies->empty()) return nullptr;
    return bodies;
  }

  /// Teammate j, driving a GoToGuarded leg (or about to: not entered yet),
  /// as the legs moving_teammates follows: the leg it drives now and the one
  /// after, times from the analysed robot's entry. Empty when nothing is
  /// known of its leg.
  std::vector<TeammateLeg> driving_legs(const BranchState& b, std::size_t j) {
    const Track& tj = b.robots[j];
    const mission::RobotSpec& spec = mission_.robots[j];
    if (entering_ != kNone && j > entering_) {
      // Not entered yet: robots enter their first state in file order at
      // launch, so the analysed robot comes before j's first leg is
      // analysed. That leg and the one after are predicted ahead from where
      // j stands (walls only), as a driving teammate's next leg is. Left
      // out, a teammate that parks by another's goal on its first legs was
      // not seen: generated gen_5115's robot2 parks 0.5 m from robot1's
      // first goal and waits, robot1 times out short of it in 992 of 1,000
      // runs, and verify had robot1 there at 85 s.
      StillChain now;
      now.seconds = 0.0;
      now.leg = tj.state;
      return legs_ahead(j, now, tj.base, tj.error, 0.0, 2);
    }
    if (tj.analysis.path.empty()) return {};
    std::vector<TeammateLeg> legs(1);
    TeammateLeg& leg = legs[0];
    leg.path = &tj.analysis.path;
    leg.start = tj.base;
    leg.end = tj.analysis.end;
    leg.error_start = tj.error.mean;
    leg.error_end = tj.analysis.error.mean;
    leg.entered_s = -std::max(0.0, b.clock.mean() - tj.entry_clock.mean());
    // The leg's own exit in this branch (the branch was split by which exit
    // fires, so there is at most one pending self-timed exit) and where it
    // leads. A Notified exit may take it out earlier: not followed.
    StillChain after;
    for (const Pending& p : tj.pending) {
      const mission::Transition& tr = spec.transitions[p.transition];
      if (std::holds_alternative<mission::NotifiedParams>(tr.trigger)) continue;
      leg.ends_in_s = std::max(0.0, p.residual.mean());
      after = still_after(j, tr.to);
      leg.still_for_s = after.seconds;
      break;
    }
    if (std::isfinite(leg.ends_in_s) && after.leg) {
      const std::vector<TeammateLeg> ahead =
          legs_ahead(j, after, tj.analysis.end, tj.analysis.error, leg.ends_in_s + leg.still_for_s, 1);
      legs.insert(legs.end(), ahead.begin(), ahead.end());
    }
    return legs;
  }

  /// What robot j does from entering `state` until it drives again.
  struct StillChain {
    /// How long it holds still (mean): 0 when `state` is a leg; infinity when
    /// it stays for good as far as its own timing goes (a final state, or one
    /// left only on a message); else the expected length of the still states
    /// it goes through by their own triggers (a Notify's acknowledgement, a
    /// Spin's turn).
    double seconds = std::numeric_limits<double>::infinity();
    std::optional<std::size_t> leg;  ///< the leg it then drives (when seconds is finite)
    std::vector<double> turns_rad;   ///< the Spins' turns on the way, in order (odometric, signed)
  };
  StillChain still_after(std::size_t j, std::size_t state) const {
    constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
    const mission::RobotSpec& spec = mission_.robots[j];
    const Kinematics& kin = robot_models_[j]->kinematics;
    StillChain chain;
    double total = 0.0;
    for (std::size_t hops = 0; hops < spec.states.size(); ++hops) {
      const mission::BehaviorParams& behavior = spec.states[state].behavior;
      if (std::holds_alternative<mission::GoToGuardedParams>(behavior)) {
        chain.seconds = total;
        chain.leg = state;
        return chain;
      }
      if (spec.is_final(state)) break;
      // The state's own exit, if it has one (file order: the executive's).
      std::optional<std::size_t> next;
      for (const std::size_t t : spec.states[state].outgoing) {
        const mission::TriggerParams& trigger = spec.transitions[t].trigger;
        if (std::holds_alternative<mission::MessageSentParams>(trigger)) {
          total += delay_in_cycles(models_.comm.ack_s, kin.cycle_s, k()).mean();
        } else if (const auto* h = std::get_if<mission::HasTurnedParams>(&trigger)) {
          const auto* spin = std::get_if<mission::SpinParams>(&behavior);
          const double rate = std::min(std::abs(spin ? spin->rate_deg_s : 0.0) * kDegToRad, kin.max_rot_vel_radps);
          if (!(rate > 0.0)) break;
          const double angle = (h->angle_deg - h->offset_deg) * kDegToRad;
          total += angle / rate + rate / kin.rot_accel_radps2;
          chain.turns_rad.push_back(spin->rate_deg_s < 0.0 ? -angle : angle);
        } else {
          continue;
        }
        next = spec.transitions[t].to;
        break;
      }
      if (!next) break;
      state = *next;
    }
    chain.seconds = std::numeric_limits<double>::infinity();
    chain.leg.reset();
    return chain;
  }

  /// The legs robot j drives after the still states of `chain` (which must
  /// lead to one), up to `count` of them, predicted ahead (look_ahead) from
  /// `from`, where those states begin, turned by their Spins and braked to
  /// rest, the first entered `entered_s` after the analysed robot's entry:
  /// the legs moving_teammates follows. Each one's exit is at the mean of its
  /// exits' durations, followed by the stillness after the likeliest one; the
  /// next leg starts from its mean end when that stillness is finite (the
  /// body drops out after the last leg given when it would drive on). Stops
  /// early where a prediction has no path.
  std::vector<TeammateLeg> legs_ahead(std::size_t j, StillChain chain, BaseState from, ErrorState error,
                                      double entered_s, std::size_t count) {
    const mission::RobotSpec& spec = mission_.robots[j];
    std::vector<TeammateLeg> legs;
    while (legs.size() < count && chain.leg) {
      BaseState start = from;
      start.trans_mps = start.rot_radps = 0.0;  // the still states in between brake
      for (const double turn : chain.turns_rad) spin_in_place(start, error, turn, robot_models_[j]->motion);
      const std::shared_ptr<const StateAnalysis> next = look_ahead(j, *chain.leg, start, error);
      if (!next || next->path.empty()) break;
      TeammateLeg ahead;
      ahead.path = &next->path;  // the analysis lives in look_ahead_cache_
      ahead.start = start;
      ahead.end = next->end;
      ahead.error_start = error.mean;
      ahead.error_end = next->error.mean;
      ahead.entered_s = entered_s;
      double mass = 0.0, mean = 0.0, best = 0.0;
      std::size_t to = 0;
      for (const TimedExit& e : next->exits) {
        mass += e.probability;
        mean += e.probability * e.duration_s.mean();
        if (e.probability > best) {
          best = e.probability;
          to = spec.transitions[e.transition].to;
        }
      }
      if (!(mass > 0.0)) {  // no self-timed exit: it drives to its goal and stays
        legs.push_back(ahead);
        break;
      }
      ahead.ends_in_s = ahead.entered_s + mean / mass;
      chain = still_after(j, to);
      ahead.still_for_s = chain.seconds;
      legs.push_back(ahead);
      if (!std::isfinite(chain.seconds)) break;
      entered_s = ahead.ends_in_s + chain.seconds;
      from = next->end;
      error = next->error;
    }
    return legs;
  }

  /// Robot j holding still now (a Notify, a Spin, a Stop) and driving off by
  /// its own triggers (still_after from the state it is in: an
  /// acknowledgement, a turn), or on a message already on its way to it
  /// (released_in): how long from now until it drives, and the chain.
  /// Nullopt when it holds still for good as far as anyone's timing goes (a
  /// final state, or one it leaves only on a message nobody has sent yet), or
  /// drives now.
  std::optional<std::pair<double, StillChain>> drives_off_in(const BranchState& b, std::size_t j) const {
    const Track& tj = b.robots[j];
    if (tj.final || std::holds_alternative<mission::GoToGuardedParams>(mission_.robots[j].states[tj.state].behavior)) {
      return std::nullopt;
    }
    StillChain chain = still_after(j, tj.state);
    if (!std::isfinite(chain.seconds) || !chain.leg) return released_in(b, j);
    const double since_entry = std::max(0.0, b.clock.mean() - tj.entry_clock.mean());
    return std::make_pair(std::max(0.0, chain.seconds - since_entry), chain);
  }

  /// Robot j waiting for a message that is already on its way (its Notified
  /// exit is pending: release_waiters): it drives off when the message lands
  /// (the pending time's mean) and the still states after it have passed.
  /// Without this a robot sent on by the Notify that releases j saw j as a
  /// wall standing where it waited for the whole of its leg, though j drives
  /// off a tenth of a second later, and steered around the empty place:
  /// tests/data/accuracy/released_teammate's robot1 finished at 35.58 +- 1.06 s
  /// where the runs say 35.43 +- 0.19 s. Nullopt when no such message is on
  /// its way.
  std::optional<std::pair<double, StillChain>> released_in(const BranchState& b, std::size_t j) const {
    const Track& tj = b.robots[j];
    const mission::RobotSpec& spec = mission_.robots[j];
    std::optional<std::pair<double, StillChain>> first;
    for (const Pending& p : tj.pending) {
      const mission::Transition& tr = spec.transitions[p.transition];
      if (!std::holds_alternative<mission::NotifiedParams>(tr.trigger)) continue;
      const double lands_in = p.detached && p.absolute ? p.absolute->mean() - b.clock.mean() : p.residual.mean();
      if (!std::isfinite(lands_in)) continue;
      StillChain after = still_after(j, tr.to);
      if (!std::isfinite(after.seconds) || !after.leg) continue;
      const double drives_in = std::max(0.0, lands_in) + after.seconds;
      if (!first || drives_in < first->first) first = std::make_pair(drives_in, std::move(after));
    }
    return first;
  }

  /// Teammate j, holding still now but driving off by itself (drives_off_in),
  /// as robot i's obstacle: standing at its mean true pose until it drives,
  /// then its next leg as a driving teammate's (absent while it drives,
  /// standing where it ends while it holds still after). Before, it stood
  /// there for the whole of i's state: a robot sent on by a teammate's Notify
  /// steered around the teammate that had just left (gen_5031's robot3 3.8 s
  /// late). Nullopt when j does not drive off by itself.
  std::optional<MovingBody> still_then_off(const BranchState& b, std::size_t j, std::size_t i) {
    const auto off = drives_off_in(b, j);
    if (!off) return std::nullopt;
    const auto& [drives_in_s, chain] = *off;
    const Track& tj = b.robots[j];
    const std::vector<TeammateLeg> legs = legs_ahead(j, chain, tj.base, tj.error, drives_in_s, 1);
    MovingBody body = follow_legs(legs, cycle_s(i));
    const Eigen::Vector2d p = tj.true_mean();
    const BodyPose here{p.x(), p.y(), tj.base.theta_rad + tj.error.mean(2)};
    const std::size_t standing = static_cast<std::size_t>(std::ceil(drives_in_s / cycle_s(i)));
    if (body.poses.size() < standing) {
      // No leg predicted (or one that ends before): stands, then gone.
      body.poses.assign(standing, here);
      body.rest_until = body.poses.size();
    } else {
      std::fill(body.poses.begin(), body.poses.begin() + static_cast<std::ptrdiff_t>(standing), here);
    }
    return body;
  }

  /// Robot j's leg `state` predicted ahead from `start`, for the teammates
  /// that will meet it there (moving_teammates): the state analysis with the
  /// walls only (who else stands where by then is not known), cached, since
  /// every robot entering a state during j's current leg asks for the same
  /// one. Its cycles count toward the work budget.
  std::shared_ptr<const StateAnalysis> look_ahead(std::size_t j, std::size_t state, const BaseState& start,
                                                  const ErrorState& error) {
    const auto key = std::make_tuple(j, state, start.x_m, start.y_m, start.theta_rad);
    if (const auto it = look_ahead_cache_.find(key); it != look_ahead_cache_.end()) return it->second;
    const auto& go = std::get<mission::GoToGuardedParams>(mission_.robots[j].states[state].behavior);
    StateContext ctx;
    ctx.robot = &mission_.robots[j];
    ctx.model = robot_models_[j];
    ctx.models = &models_;
    ctx.obstacles = segments_near(walls_, start.x_m + error.mean(0), start.y_m + error.mean(1), go.goal.x_m, go.goal.y_m,
                                  models_.environment.sonar_max_range_m + 1.0);
    ctx.walls = ctx.obstacles;
    auto a = std::make_shared<const StateAnalysis>(analyze_state(ctx, state, start, error));
    outcome_.work_cycles += a->cycles_simulated;
    look_ahead_cache_.emplace(key, a);
    return a;
  }

  /// A Notify of message m: robots already waiting for it now have a pending exit.
  void release_waiters(BranchState& b, std::size_t m) {
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      Track& t = b.robots[j];
      if (t.final) continue;
      const mission::RobotSpec& spec = mission_.robots[j];
      for (const std::size_t tr : spec.states[t.state].outgoing) {
        const auto* n = std::get_if<mission::NotifiedParams>(&spec.transitions[tr].trigger);
        if (n == nullptr || n->message != mission_.messages[m].name) continue;
        const bool already = std::any_of(t.pending.begin(), t.pending.end(), [&](const Pending& p) { return p.transition == tr; });
        if (!already) t.pending.push_back({tr, *b.delivery[m], {}, b.delivery_at[m], b.delivery_lineage[m]});
      }
    }
  }

  /// Robot i's predicted path through the state it has just entered, on its
  /// timeline from the branch clock (what it had predicted from then on, for
  /// the state it left, is dropped).
  void note_path(BranchState& b, std::size_t i) {
    Track& t = b.robots[i];
    const double t0 = b.clock.mean();
    const std::vector<PathSample>& path = t.analysis.path;
    const double rigid = rigid_span(i, t.state, path.empty() ? 0.0 : path.back().offset_s);
    t.timeline.note(t0, t.true_position(), rigid);
    if (path.empty()) return;
    // The true pose's error goes from the entry's to the state's end's (the
    // analysis's) along the distance driven, as for a teammate's body
    // (engine/moving_bodies): a heading error turns the path about its start,
    // so a robot whose wheels differ drives a straight line off its
    // odometry's, metres off by the leg's end.
    std::vector<double> driven(path.size(), 0.0);
    for (std::size_t k = 1; k < path.size(); ++k) {
      driven[k] = driven[k - 1] + std::hypot(path[k].x_m - path[k - 1].x_m, path[k].y_m - path[k - 1].y_m);
    }
    const double total = driven.back();
    const Eigen::Vector2d entry_mean = t.error.mean.head<2>();
    const Eigen::Vector2d mean_growth = t.analysis.error.mean.head<2>() - entry_mean;
    const Eigen::Matrix2d entry_cov = t.error.cov.topLeftCorner<2, 2>();
    const Eigen::Matrix2d cov_growth = floored_psd(t.analysis.error.cov.topLeftCorner<2, 2>() - entry_cov);
    // When it entered the state is known only as the branch clock's spread:
    // at a given mission time it is that much further along its path, or
    // behind (its velocity there times the clock's sd).
    const double entry_var = b.clock.variance();
    for (std::size_t k = 0; k < path.size(); ++k) {
      const PathSample& s = path[k];
      if (!(s.offset_s > 0.0)) continue;  // the entry, noted above
      const double f = total > 1e-6 ? driven[k] / total : s.offset_s / std::max(path.back().offset_s, 1e-9);
      Gaussian2 p;
      p.mean = Eigen::Vector2d(s.x_m, s.y_m) + entry_mean + f * mean_growth;
      Eigen::Matrix2d paths;
      paths << s.var_xx, s.var_xy, s.var_xy, s.var_yy;
      const PathSample& before = path[k > 0 ? k - 1 : k];
      const PathSample& after = path[std::min(k + 1, path.size() - 1)];
      const double span = after.offset_s - before.offset_s;
      const Eigen::Vector2d velocity = Eigen::Vector2d(after.x_m - before.x_m, after.y_m - before.y_m) / std::max(span, 1e-9);
      p.cov = t.spread + entry_cov + f * cov_growth + paths + entry_var * velocity * velocity.transpose();
      t.timeline.note(t0 + s.offset_s, p, rigid);
    }
  }

  /// For how long robot i's error in `state` (a path of `path_s` seconds)
  /// can be taken as one fixed draw: a NOISE redrawn within the leg moves it
  /// off its mean path afresh at every draw; otherwise (held for the leg, or
  /// none) the stretch's limit.
  double rigid_span(std::size_t i, std::size_t state, double path_s) const {
    const auto* go = std::get_if<mission::GoToGuardedParams>(&mission_.robots[i].states[state].behavior);
    if (go == nullptr || !(go->noise_gain > 0.0) || go->noise_persistence_cycles <= 0) return kSeparationWindowS;
    const double held_s = static_cast<double>(go->noise_persistence_cycles) * cycle_s(i);
    return held_s >= path_s ? kSeparationWindowS : std::min(kSeparationWindowS, std::max(held_s, cycle_s(i)));
  }

  /// One event (Def. 10 step) of branch b: the first abort condition to hold.
  void advance(BranchState b, std::vector<BranchState>& out) {
    struct Candidate {
      std::size_t robot, index;
    };
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < b.robots.size(); ++i) {
      for (std::size_t p = 0; p < b.robots[i].pending.size(); ++p) {
        // An exit whose time has no mass left never fires (its residual is
        // empty): compared as a rival it would leave none plausible.
        if (!b.robots[i].pending[p].residual.components.empty()) candidates.push_back({i, p});
      }
    }
    if (candidates.empty()) {
      const bool done = std::all_of(b.robots.begin(), b.robots.end(), [](const Track& t) { return t.final; });
      if (done) finish(std::move(b));
      else {
        outcome_.blocked_mass += b.weight;  // someone waits for a message nobody will send
        note_unfinished(b, "waiting");
      }
      return;
    }
    const auto residual = [&](const Candidate& c) -> const Mixture1& { return b.robots[c.robot].pending[c.index].residual; };

    // Only candidates that can plausibly fire first are compared: one whose
    // earliest plausible time is after another's latest cannot be first. This
    // keeps an event's cost independent of how many robots are busy elsewhere.
    double earliest_latest = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, double>> span(candidates.size());
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      span[c] = plausible_span(residual(candidates[c]));
      earliest_latest = std::min(earliest_latest, span[c].second);
    }
    std::vector<std::size_t> rivals;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (span[c].first <= earliest_latest) rivals.push_back(c);
    }

    // Which fires first: P(R_c < R_o for every other rival o), normalised.
    // Two rivals: the pairwise probability. Three or more whose times are
    // mutually independent (disjoint lineages: robots that have not heard
    // from each other): the joint probability by quadrature over the race on
    // their absolute times (first_probabilities). Otherwise the product of
    // pairwise probabilities: one robot's own exits, or times that share
    // history, are not independent, and the product is what was validated.
    std::vector<double> first(rivals.size(), 1.0);
    double total = 0.0;
    bool joint = false;
    if (rivals.size() >= 3) {
      bool apart = true;
      for (std::size_t c = 0; c < rivals.size() && apart; ++c) {
        const Pending& pc = b.robots[candidates[rivals[c]].robot].pending[candidates[rivals[c]].index];
        for (std::size_t o = c + 1; o < rivals.size() && apart; ++o) {
          const Pending& po = b.robots[candidates[rivals[o]].robot].pending[candidates[rivals[o]].index];
          apart = pc.absolute && po.absolute && independent(pc.lineage, po.lineage);
        }
      }
      if (apart) {
        std::vector<const Mixture1*> xs;
        for (const std::size_t r : rivals) xs.push_back(&*b.robots[candidates[r].robot].pending[candidates[r].index].absolute);
        first = first_probabilities(xs);
        joint = true;
      }
    }
    for (std::size_t c = 0; c < rivals.size() && !joint; ++c) {
      for (std::size_t o = 0; o < rivals.size() && first[c] > kNegligible; ++o) {
        if (o == c) continue;
        const Pending& pc = b.robots[candidates[rivals[c]].robot].pending[candidates[rivals[c]].index];
        const Pending& po = b.robots[candidates[rivals[o]].robot].pending[candidates[rivals[o]].index];
        if (pc.absolute && po.absolute && independent(pc.lineage, po.lineage)) {
          first[c] *= probability_less(*pc.absolute, *po.absolute);
        } else {
          first[c] *= probability_less(widened(pc.residual, comparison_var(pc.hidden, po.hidden)), po.residual);
        }
      }
    }
    for (const double f : first) total += f;
    if (!(total > 0.0)) {  // ties everywhere (identical point masses): file order decides
      first.assign(rivals.size(), 0.0);
      first[0] = 1.0;
      total = 1.0;
    }
    if (std::count_if(first.begin(), first.end(), [&](double f) { return f / total >= kNegligible; }) > 1) {
      ++outcome_.ordering_splits;
    }
    {
      std::vector<std::size_t> racing;
      for (std::size_t c = 0; c < rivals.size(); ++c) {
        if (first[c] / total >= kNegligible) racing.push_back(candidates[rivals[c]].robot);
      }
      note_race(b, racing);
    }
    for (std::size_t c = 0; c < rivals.size(); ++c) {
      const double p = first[c] / total;
      if (p < kNegligible) {
        outcome_.pruned_mass += b.weight * p;
        continue;
      }
      // The usual case, one sure winner, takes the branch itself: copying it
      // (its trace and samples grow with the mission) at every event would
      // make the evaluation quadratic in the mission's length.
      const bool sure = p > 1.0 - kNegligible;
      const Candidate winner = candidates[rivals[c]];
      BranchState child = sure ? std::move(b) : b;
      child.weight *= p;
      const Mixture1 r_c_raw = child.robots[winner.robot].pending[winner.index].residual;
      Mixture1 r_c = r_c_raw;
      // The event's mission time: its own absolute time when that is
      // independent of the clock (conditioned on being before its
      // independent rivals), else the clock plus the residual.
      const Pending& wp = child.robots[winner.robot].pending[winner.index];
      std::optional<Mixture1> at;
      // A detached time (see Pending) is its absolute time too, whatever the
      // clock's lineage became since (a merge of branches whose clocks were
      // set by different robots ORs their lineages).
      if (wp.absolute && (wp.detached || independent(wp.lineage, child.clock_lineage))) at = *wp.absolute;
      if (!sure) {
        for (std::size_t o = 0; o < rivals.size(); ++o) {
          if (o == c) continue;
          const Candidate& rival = candidates[rivals[o]];
          const Pending& rp = child.robots[rival.robot].pending[rival.index];
          double q = 0.0;
          const Mixture1 cond = conditioned_less(r_c, rp.residual, k(), q);
          if (!cond.components.empty() && q > 0.0) r_c = cond;
          if (at && rp.absolute && independent(wp.lineage, rp.lineage)) {
            double qa = 0.0;
            const Mixture1 cond_at = conditioned_less(*at, *rp.absolute, k(), qa);
            if (!cond_at.components.empty() && qa > 0.0) at = cond_at;
          }
        }
      }
      fire(std::move(child), winner.robot, winner.index, r_c, r_c_raw, at, out);
      if (sure) break;
    }
  }

  void fire(BranchState b, std::size_t i, std::size_t pending_index, const Mixture1& elapsed, const Mixture1& elapsed_raw,
            const std::optional<Mixture1>& at, std::vector<BranchState>& out) {
    const std::size_t transition = b.robots[i].pending[pending_index].transition;
    const HiddenList winner_hidden = b.robots[i].pending[pending_index].hidden;
    const Lineage winner_lineage = b.robots[i].pending[pending_index].lineage;
    const std::size_t event = b.event_robots.size();
    if (at) {
      b.clock = *at;
      b.clock_lineage = winner_lineage;
    } else {
      b.clock = sum(b.clock, elapsed, k());
      b.clock_lineage |= winner_lineage;
    }
    // Times independent of this event are later than it (it came first).
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      if (j == i) continue;
      for (Pending& p : b.robots[j].pending) {
        if (!p.absolute || !independent(p.lineage, b.clock_lineage)) continue;
        if (plausible_span(*p.absolute).first > plausible_span(b.clock).second) continue;
        double q = 0.0;
        const Mixture1 later = conditioned_greater(*p.absolute, b.clock, k(), q);
        if (!later.components.empty() && q > 0.0) p.absolute = later;
      }
    }
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      Track& tj = b.robots[j];
      // The time since each robot's state entry grows by this event's
      // elapsed time (the firing robot's too: its interruption time).
      if (!tj.final) {
        tj.since_entry = sum(tj.since_entry, elapsed, k());
        for (const Hidden& h : winner_hidden) {
          if (h.event < tj.entry_events) tj.since_hidden += 2.0 * h.var;
        }
      }
      if (j == i) continue;
      for (Pending& p : tj.pending) {
        p.residual = remaining_after(p.residual, elapsed_raw, k(), &p.hidden, event);
        // Relative to an independent event's time, the residual no longer
        // adds to the clock to give this time: it fires at its absolute time.
        if (independent(p.lineage, winner_lineage)) p.detached = true;
      }
    }
    for (std::optional<Mixture1>& d : b.delivery) {
      if (!d) continue;
      if (d->components.size() == 1 && d->components[0].mean == 0.0 && d->components[0].var == 0.0) continue;
      // Delivered for sure: nothing left to track (most messages, most of the
      // time). The test is on the message's latest plausible delivery, since a
      // moment-matched max(D - R, 0) keeps a small spread above 0 forever.
      if (plausible_span(*d).second <= plausible_span(elapsed).first) {
        d = Mixture1::point(0.0);
        continue;
      }
      d = maximum(sum(*d, negated(elapsed), k()), 0.0);
    }
    b.event_robots.push_back(i);
    Track& t = b.robots[i];
    const mission::RobotSpec& spec = mission_.robots[i];
    const bool by_message = std::holds_alternative<mission::NotifiedParams>(spec.transitions[transition].trigger);
    // A robot taken on by a message goes on at the message's time.
    if (by_message) t.lineage = winner_lineage | lineage_of(i);
    if (by_message && t.analysis.trajectory) {
      interrupt(std::move(b), i, transition, out);
      return;
    }
    t.interruption_bin = 0;
    // Where the state ends, moved with a start merged after its analysis.
    const BaseState end = moved_with_start(t, i, t.analysis.end);
    // The earlier paths' errors ride along this state's displacement; this
    // state's own paths add theirs (independent draws of NOISE).
    transport(t.error_mix, end.x_m - t.base.x_m, end.y_m - t.base.y_m);
    transport(t.error_mix_before_leg, end.x_m - t.base.x_m, end.y_m - t.base.y_m);
    if (t.analysis.sets_spread) {
      t.error_mix_before_leg = t.error_mix;
      t.leg_paths_cov = explained_cov(t.analysis.error_paths).topLeftCorner<2, 2>();
    }
    t.error_mix = convolve(t.error_mix, t.analysis.error_paths, kMaxErrorComponents);
    t.start_points = t.analysis.end_points;
    for (StartPoint& p : t.start_points) p.q = moved_with_start(t, i, p.q);
    t.base = end;
    t.error = t.analysis.error;
    if (t.analysis.sets_spread) {
      t.spread = t.analysis.end_spread;
      t.spread_points = t.analysis.end_offsets;
      t.spread_weights = t.analysis.end_weights;
      t.spread_points_within = t.analysis.end_offsets_within;
      t.spread_delays = t.analysis.end_delays;
      t.rest_points = t.analysis.rest_offsets;
      t.rest_weights = t.analysis.rest_weights;
      t.rest_points_within = t.analysis.rest_offsets_within;
      t.rest_delays = t.analysis.rest_delays;
      t.extra_cov.setZero();
    }
    t.timeline.note(b.clock.mean(), t.true_position(), kSeparationWindowS);
    enter(std::move(b), i, spec.transitions[transition].to, out);
  }

  /// A message takes robot i out of a motion state (b's clock is already at
  /// the event): the robot is where its leg has got to at the interruption
  /// time τ (since the state's entry), one branch per bin of τ.
  void interrupt(BranchState b, std::size_t i, std::size_t transition, std::vector<BranchState>& out) {
    Track& t = b.robots[i];
    // The time since the state's entry: the difference of two independent
    // times when the clock and the entry were decided by different robots,
    // else the clock's increments since the entry.
    const bool apart = independent(t.entry_lineage, b.clock_lineage);
    Mixture1 tau = apart ? maximum(sum(b.clock, negated(t.entry_clock), k()), 0.0) : widened(t.since_entry, t.since_hidden);
    if (apart) reduce(tau, k());
    const std::vector<InterruptionBin> bins = interruption_bins(*t.analysis.trajectory, tau, kInterruptionBins);
    // The clock given τ's bin (Gaussian conditioning on the moments): the
    // clock is the entry's clock plus τ, the two correlated as their
    // variances say (Cov(C, E) from Var τ = Var C + Var E - 2 Cov(C, E)).
    const double var_c = b.clock.variance(), var_e = t.entry_clock.variance(), var_tau = tau.variance();
    const double mean_c = b.clock.mean(), mean_tau = tau.mean();
    const double cov_c_tau = 0.5 * (var_c - var_e + var_tau);
    const double beta = var_tau > 1e-12 ? std::clamp(cov_c_tau / var_tau, 0.0, 1.0) : 0.0;
    const std::size_t to = mission_.robots[i].transitions[transition].to;
    for (std::size_t k_bin = 0; k_bin < bins.size(); ++k_bin) {
      const InterruptionBin& bin = bins[k_bin];
      if (bin.probability < kNegligible) {
        outcome_.pruned_mass += b.weight * bin.probability;
        continue;
      }
      BranchState child = k_bin + 1 == bins.size() ? std::move(b) : b;
      child.weight *= bin.probability;
      if (bins.size() > 1) {
        const double var = std::max(0.0, var_c - beta * beta * var_tau + beta * beta * bin.tau_var_s2);
        child.clock = Mixture1::gaussian(mean_c + beta * (bin.tau_mean_s - mean_tau), var);
      }
      Track& ti = child.robots[i];
      ti.interruption_bin = bins.size() > 1 ? k_bin + 1 : 0;
      // The bin's place, moved with a start merged after the analysis; the
      // spread around the start that the analysis's paths do not carry (in
      // extra_cov: a merge's, an earlier interruption's) is carried by the
      // share of the leg still ahead, as the start itself is.
      const BaseState place = moved_with_start(ti, i, bin.base);
      const double ahead = share_ahead(ti, i, bin.base);
      // Only the earlier paths' errors are kept apart here; the interrupted
      // leg's own spread between paths is in bin.error's covariance.
      transport(ti.error_mix, place.x_m - ti.base.x_m, place.y_m - ti.base.y_m);
      ti.error_mix_before_leg = ti.error_mix;  // the bin's offsets are odometric only
      ti.leg_paths_cov.setZero();
      ti.spread_points_within.setZero();
      ti.base = place;
      ti.start_points.clear();
      {
        std::vector<StartPoint> points;
        std::vector<double> keys;
        for (std::size_t j = 0; j < bin.path_offsets.size(); ++j) {
          BaseState q = place;
          q.x_m += bin.path_offsets[j].x();
          q.y_m += bin.path_offsets[j].y();
          q.theta_rad = bin.headings[j];
          points.push_back({q, Eigen::Vector3d::Zero()});
          keys.push_back(static_cast<double>(j));
        }
        ti.start_points = equal_weight_points(points, bin.weights, keys, kStartPointsCarried);
      }
      ti.error = bin.error;
      ti.spread = bin.spread;
      ti.spread_points = bin.offsets;
      ti.spread_weights.clear();
      ti.spread_delays.clear();  // where a message stopped it, not when its paths arrived
      ti.extra_cov = bin.within + ahead * ahead * ti.extra_cov;
      ti.timeline.note(child.clock.mean(), ti.true_position(), kSeparationWindowS);
      enter(std::move(child), i, to, out);
    }
  }

  /// The share of robot i's current state still ahead of a pose of its
  /// analysis (engine/moved_start.hpp): how much of a start merged after
  /// the analysis the pose moves with.
  double share_ahead(const Track& t, std::size_t i, const BaseState& pose) const {
    std::optional<Eigen::Vector2d> goal;
    if (const auto* go = std::get_if<mission::GoToGuardedParams>(&mission_.robots[i].states[t.state].behavior)) {
      goal = Eigen::Vector2d(go->goal.x_m, go->goal.y_m);
    }
    const Eigen::Vector2d analysis_start = Eigen::Vector2d(t.base.x_m, t.base.y_m) - t.moved_start;
    return share_still_ahead(analysis_start, goal, Eigen::Vector2d(pose.x_m, pose.y_m));
  }

  /// A pose of robot i's current analysis, moved with its merged start.
  BaseState moved_with_start(const Track& t, std::size_t i, BaseState pose) const {
    if (t.moved_start.isZero()) return pose;
    const double share = share_ahead(t, i, pose);
    pose.x_m += share * t.moved_start.x();
    pose.y_m += share * t.moved_start.y();
    return pose;
  }

  void finish(BranchState b) {
    outcome_.budget_merged_mass += b.weight * b.coarse;
    Branch out;
    out.weight = b.weight;
    out.completion_time_s = b.clock;
    std::vector<const Timeline*> timelines;
    for (const Track& t : b.robots) timelines.push_back(&t.timeline);
    out.separations = pair_separations(timelines, kSeparationHorizonM);
    out.event_robots = std::move(b.event_robots);
    for (Track& t : b.robots) {
      RobotOutcome r;
      r.finish_time_s = t.finish;
      r.final_position = t.true_position();
      // The mixture the final position is: one component per NOISE path end
      // point of the last leg and per error component kept apart (each with
      // its own spread plus the error's common covariance); without end
      // points, their Gaussian spread goes into every component.
      if (!t.spread_points.empty() || !t.error_mix.empty()) {
        // With end points, they carry the last leg's paths' errors; without,
        // the whole mixture does.
        // (turned onto the total's axis where the two describe one spread:
        // error_mixture.hpp, aligned_to_total)
        const ErrorMixture kept = aligned_to_total(t.spread_points.empty() ? t.error_mix : t.error_mix_before_leg,
                                                   t.error.cov.topLeftCorner<2, 2>());
        Eigen::Matrix2d shown = explained_cov(kept).topLeftCorner<2, 2>();
        if (!t.spread_points.empty()) shown += t.leg_paths_cov;
        const Eigen::Matrix2d common = floored_psd(t.error.cov.topLeftCorner<2, 2>() - shown) + t.extra_cov +
                                       (t.spread_points.empty() ? t.spread : t.spread_points_within);
        const std::vector<Eigen::Vector2d> ends =
            t.spread_points.empty() ? std::vector<Eigen::Vector2d>{Eigen::Vector2d::Zero()} : t.spread_points;
        const ErrorMixture mix = kept.empty() ? ErrorMixture{ErrorComponent{}} : kept;
        const std::vector<double> scores = time_scores(t, ends.size(), r.time_score_correlation);
        for (std::size_t e = 0; e < ends.size(); ++e) {
          for (const ErrorComponent& c : mix) {
            Gaussian2 g;
            g.mean = t.true_mean() + ends[e] + c.delta.head<2>();
            g.cov = common + c.cov.topLeftCorner<2, 2>();
            r.final_components.push_back(g);
            r.final_weights.push_back(t.spread_weights.empty() ? c.weight / static_cast<double>(ends.size())
                                                               : c.weight * t.spread_weights[e]);
            if (!scores.empty()) r.final_time_scores.push_back(scores[e]);
          }
        }
      }
      r.believed_position = Eigen::Vector2d(t.base.x_m, t.base.y_m);
      r.states = std::move(t.trace);
      r.finished = t.final;
      out.robots.push_back(std::move(r));
    }
    outcome_.branches.push_back(std::move(out));
  }

  /// The last leg's end points' delays standardised (equal weights: mean 0,
  /// variance 1), and `rho` set to their correlation with the robot's finish
  /// time: their spread's share of the finish time's (the rest of it, the
  /// earlier states' and the paths' own widths, is independent of which
  /// point). Empty, and rho 0, when the points' delays are not known or do
  /// not vary. Capped at 0.95: the paths are 8 points standing for a circle.
  static std::vector<double> time_scores(const Track& t, std::size_t ends, double& rho) {
    rho = 0.0;
    if (!t.final || t.spread_points.empty() || t.spread_delays.size() != ends) return {};
    double mean = 0.0, var = 0.0;
    for (const double d : t.spread_delays) mean += d / static_cast<double>(ends);
    for (const double d : t.spread_delays) var += (d - mean) * (d - mean) / static_cast<double>(ends);
    const double finish_var = t.finish.variance();
    if (!(var > 1e-12) || !(finish_var > 0.0) || !std::isfinite(finish_var)) return {};
    rho = std::min(0.95, std::sqrt(var / finish_var));
    std::vector<double> z;
    for (const double d : t.spread_delays) z.push_back((d - mean) / std::sqrt(var));
    return z;
  }

  /// Branches in the same discrete configuration become one (moment-matched);
  /// then only the heaviest max_branches go on.
  std::vector<BranchState> merge_and_prune(std::vector<BranchState> branches) {
    std::map<std::string, std::vector<std::size_t>> by_key;
    std::vector<BranchState> merged;
    for (BranchState& b : branches) {
      std::vector<std::size_t>& same = by_key[configuration_key(b)];
      // Into the first branch of the configuration whose robots are where
      // this one's are (engine/moved_start.hpp, close_enough_to_merge).
      const auto into = std::find_if(same.begin(), same.end(), [&](std::size_t m) { return same_places(merged[m], b); });
      if (into == same.end()) {
        same.push_back(merged.size());
        merged.push_back(std::move(b));
      } else {
        merge_into(merged[*into], b);
      }
    }
    const auto heavier_first = [](const BranchState& a, const BranchState& b) { return a.weight > b.weight; };
    std::stable_sort(merged.begin(), merged.end(), heavier_first);
    const std::size_t keep = std::max<std::size_t>(1, models_.budget.max_branches);
    if (merged.size() <= keep) return merged;
    // Over the budget. Dropping a branch counts its mass as failure, and a
    // recall mid-leg splits a branch into twelve (one per bin of where the
    // message found the robot) that stay apart until the robot's next event:
    // gen_7162 (five robots, three recalls, a patrol) dropped 0.90 of its
    // mass at 32 branches, 0.19 at 256 (20 s), nearly all of it bins. So,
    // lightest first, a branch beyond the budget joins the nearest heavier
    // branch in its configuration but for such bins, wherever its robots are
    // (merge_into: the mean place, the spread between them kept), until the budget holds or
    // nothing is left to join; only then are the lightest dropped. Bins
    // merged this way are a coarser picture of where the robots are, not a
    // lost one; the mass so merged is reported (budget_merged_mass) and makes
    // the answer one the gate does not vouch for.
    std::vector<std::string> keys_but_bins(merged.size());
    std::map<std::string, std::vector<std::size_t>> by_places;
    for (std::size_t m = 0; m < merged.size(); ++m) {
      keys_but_bins[m] = configuration_key(merged[m], false);
      by_places[keys_but_bins[m]].push_back(m);
    }
    std::vector<bool> joined(merged.size(), false);
    std::size_t left = merged.size();
    for (std::size_t m = merged.size(); m-- > 1 && left > keep;) {
      std::size_t nearest = m;
      double nearest_d2 = std::numeric_limits<double>::infinity();
      for (const std::size_t into : by_places[keys_but_bins[m]]) {
        if (into >= m) continue;  // heavier ones only (sorted), none of them joined yet
        double d2 = 0.0;
        for (std::size_t i = 0; i < merged[m].robots.size(); ++i) {
          d2 += (merged[into].robots[i].true_mean() - merged[m].robots[i].true_mean()).squaredNorm();
        }
        if (d2 < nearest_d2) nearest_d2 = d2, nearest = into;
      }
      if (nearest == m) continue;
      const bool apart = note_budget_merge(merged[nearest], merged[m]);
      merge_into(merged[nearest], merged[m]);
      if (apart) merged[nearest].coarse = 1.0;
      joined[m] = true;
      --left;
    }
    std::vector<BranchState> kept;
    kept.reserve(left);
    for (std::size_t m = 0; m < merged.size(); ++m) {
      if (!joined[m]) kept.push_back(std::move(merged[m]));
    }
    std::stable_sort(kept.begin(), kept.end(), heavier_first);
    while (kept.size() > keep) {
      outcome_.pruned_mass += kept.back().weight;
      kept.pop_back();
    }
    return kept;
  }

  /// Whether every robot of a and b is close enough to merge its places.
  static bool same_places(const BranchState& a, const BranchState& b) {
    for (std::size_t i = 0; i < a.robots.size(); ++i) {
      const Gaussian2 pa = a.robots[i].true_position(), pb = b.robots[i].true_position();
      if (!close_enough_to_merge(pa.mean, pa.cov, pb.mean, pb.cov)) return false;
    }
    return true;
  }

  /// The discrete configuration: each robot's state, its pending exits, the
  /// bin of a fresh interruption (`with_bins`), and which messages are under way.
  std::string configuration_key(const BranchState& b, bool with_bins = true) const {
    std::string key;
    for (const Track& t : b.robots) {
      key += std::to_string(t.state) + (t.final ? "F" : "") + "/" + std::to_string(with_bins ? t.interruption_bin : 0) + "[";
      for (const Pending& p : t.pending) key += std::to_string(p.transition) + ",";
      key += "]";
    }
    key += "|";
    for (const auto& d : b.delivery) key += d ? '1' : '0';
    return key;
  }

  void merge_into(BranchState& a, const BranchState& b) const {
    const double wa = a.weight, wb = b.weight, w = wa + wb;
    if (!(w > 0.0)) return;
    a.clock = blend(a.clock, wa, b.clock, wb, k());
    for (std::size_t i = 0; i < a.robots.size(); ++i) {
      Track& ta = a.robots[i];
      const Track& tb = b.robots[i];
      for (std::size_t p = 0; p < ta.pending.size(); ++p) {
        Pending& pa = ta.pending[p];
        const Pending& pb = tb.pending[p];
        pa.residual = blend(pa.residual, wa, pb.residual, wb, k());
        if (pa.absolute && pb.absolute) pa.absolute = blend(*pa.absolute, wa, *pb.absolute, wb, k());
        else pa.absolute.reset();
        pa.lineage |= pb.lineage;
        pa.detached = pa.detached || pb.detached;  // the absolute is right for both; the residual for neither
      }
      ta.lineage |= tb.lineage;
      ta.entry_lineage |= tb.entry_lineage;
      if (ta.final) ta.finish = blend(ta.finish, wa, tb.finish, wb, k());
      ta.since_entry = blend(ta.since_entry, wa, tb.since_entry, wb, k());
      ta.since_hidden = (wa * ta.since_hidden + wb * tb.since_hidden) / w;
      ta.entry_clock = blend(ta.entry_clock, wa, tb.entry_clock, wb, k());
      const ErrorState errors[2] = {ta.error, tb.error};
      const double ws[2] = {wa, wb};
      ta.error_mix = blend_branches(ta.error_mix, ta.error.mean, wa, tb.error_mix, tb.error.mean, wb, kMaxErrorComponents);
      ta.error_mix_before_leg = blend_branches(ta.error_mix_before_leg, ta.error.mean, wa, tb.error_mix_before_leg,
                                               tb.error.mean, wb, kMaxErrorComponents);
      ta.leg_paths_cov = (wa * ta.leg_paths_cov + wb * tb.leg_paths_cov) / w;
      ta.spread_points_within = (wa * ta.spread_points_within + wb * tb.spread_points_within) / w;
      ta.error = combine(errors, ws, 2);
      ta.spread = (wa * ta.spread + wb * tb.spread) / w;
      // Both branches' start points, each weighted by its branch, as equally
      // likely points again (in order of heading: turns one way or the other).
      if (!ta.start_points.empty() || !tb.start_points.empty()) {
        std::vector<StartPoint> points;
        std::vector<double> weights, keys;
        const auto add = [&](const std::vector<StartPoint>& from, const BaseState& base, double share) {
          if (from.empty()) {
            BaseState q = base;
            q.theta_rad = ta.base.theta_rad + std::remainder(q.theta_rad - ta.base.theta_rad, 2.0 * 3.14159265358979323846);
            points.push_back({q, Eigen::Vector3d::Zero()});
            weights.push_back(share);
          } else {
            for (StartPoint p : from) {
              p.q.theta_rad = ta.base.theta_rad + std::remainder(p.q.theta_rad - ta.base.theta_rad, 2.0 * 3.14159265358979323846);
              points.push_back(p);
              weights.push_back(share / static_cast<double>(from.size()));
            }
          }
        };
        add(ta.start_points, ta.base, wa / w);
        add(tb.start_points, tb.base, wb / w);
        for (const StartPoint& p : points) keys.push_back(std::remainder(p.q.theta_rad - ta.base.theta_rad, 2.0 * 3.14159265358979323846));
        ta.start_points = equal_weight_points(points, weights, keys, kStartPointsCarried);
      }
      // Point j of both is the end of the same NOISE direction: blend them
      // (and their delays) pointwise; lists that do not match fall back to
      // the Gaussian (and to no delays).
      const auto blend_pointwise = [&](auto& pa, const auto& pb) {
        if (pa.size() != pb.size()) {
          pa.clear();
          return;
        }
        for (std::size_t j = 0; j < pa.size(); ++j) pa[j] = (wa * pa[j] + wb * pb[j]) / w;
      };
      // Points with their own weights (an empty list: equally likely) blend
      // the weights alike; points that do not match drop them with the points.
      const auto blend_weighted = [&](std::vector<Eigen::Vector2d>& pa, std::vector<double>& qa,
                                      const std::vector<Eigen::Vector2d>& pb, const std::vector<double>& qb) {
        const std::size_t n = pa.size();
        if (pb.size() != n) {
          qa.clear();
        } else if (!qa.empty() || !qb.empty()) {
          const auto at = [n](const std::vector<double>& q, std::size_t j) {
            return q.size() == n ? q[j] : 1.0 / static_cast<double>(n);
          };
          std::vector<double> out(n);
          for (std::size_t j = 0; j < n; ++j) out[j] = (wa * at(qa, j) + wb * at(qb, j)) / w;
          qa = std::move(out);
        }
        blend_pointwise(pa, pb);
      };
      blend_weighted(ta.spread_points, ta.spread_weights, tb.spread_points, tb.spread_weights);
      blend_weighted(ta.rest_points, ta.rest_weights, tb.rest_points, tb.rest_weights);
      blend_pointwise(ta.spread_delays, tb.spread_delays);
      blend_pointwise(ta.rest_delays, tb.rest_delays);
      ta.rest_points_within = (wa * ta.rest_points_within + wb * tb.rest_points_within) / w;
      ta.extra_cov = (wa * ta.extra_cov + wb * tb.extra_cov) / w;
      // Entered (or left) from different places: an interruption's bins once
      // the robot's next event has made them one configuration, teammates
      // that met it in different orders. The merged start is the mean of the
      // two; a's analysis goes on, moved with it (moved_start), and the
      // spread between the two starts is kept as a position spread of its own
      // (extra_cov), which a leg to a goal gives up as it gets there. Keeping
      // a's start alone put gen_7093's robot1, recalled within a second of
      // starting, where the earliest recall left it: 5 mm from its start with
      // a spread of 0.6 mm, where the runs end 54 +- 44 mm from it.
      const Eigen::Vector2d from_a(ta.base.x_m, ta.base.y_m), from_b(tb.base.x_m, tb.base.y_m);
      const Eigen::Vector2d apart = from_b - from_a;
      if (!apart.isZero()) {
        const Eigen::Vector2d mean = from_a + (wb / w) * apart;
        ta.extra_cov += (wa * wb / (w * w)) * apart * apart.transpose();
        ta.moved_start += mean - from_a;
        ta.base.x_m = mean.x();
        ta.base.y_m = mean.y();
      }
      ta.base.theta_rad += (wb / w) * std::remainder(tb.base.theta_rad - ta.base.theta_rad, 2.0 * 3.14159265358979323846);
      ta.base.trans_mps = (wa * ta.base.trans_mps + wb * tb.base.trans_mps) / w;
      ta.base.rot_radps = (wa * ta.base.rot_radps + wb * tb.base.rot_radps) / w;
    }
    for (std::size_t m = 0; m < a.delivery.size(); ++m) {
      if (a.delivery[m] && b.delivery[m]) a.delivery[m] = blend(*a.delivery[m], wa, *b.delivery[m], wb, k());
      if (a.delivery_at[m] && b.delivery_at[m]) a.delivery_at[m] = blend(*a.delivery_at[m], wa, *b.delivery_at[m], wb, k());
      a.delivery_lineage[m] |= b.delivery_lineage[m];
    }
    a.clock_lineage |= b.clock_lineage;
    a.coarse = (wa * a.coarse + wb * b.coarse) / w;
    if (wb > wa) {
      a.event_robots = b.event_robots;
      for (std::size_t i = 0; i < a.robots.size(); ++i) {
        a.robots[i].trace = b.robots[i].trace;
        a.robots[i].timeline = b.robots[i].timeline;
      }
    }
    a.weight = w;
  }

  // ---- facts for the approximations check (outcome.hpp: BlockedRecord,
  // RaceRecord, ConcurrentLegs); deduplicated, so their cost is bounded by
  // the mission's size, not by the number of branches or events.

  /// Notes the robots whose places differ between a and b, about to be
  /// merged over the budget; whether there are any. Any difference counts,
  /// not only one beyond close_enough_to_merge: merging the lightest bin into
  /// its neighbour again and again passes that test each time (the merged
  /// place widens as it goes), and recall_mid_leg's twelve bins so merged
  /// into one said P(r <= Rmax) 0.386 where the twelve say 0.319.
  static constexpr double kSamePlaceM = 0.02;  ///< close_enough_to_merge's floor
  bool note_budget_merge(const BranchState& a, const BranchState& b) {
    bool apart = false;
    for (std::size_t i = 0; i < a.robots.size(); ++i) {
      if ((a.robots[i].true_mean() - b.robots[i].true_mean()).norm() <= kSamePlaceM) continue;
      apart = true;
      note_budget_merge_of(i, a.robots[i].state, false);
    }
    return apart;
  }

  /// Records (once per robot and state) that robot i's places in `state`
  /// were merged to keep within a budget: the work budget's (a reused
  /// analysis) or the branch budget's, each said in the approximation's text.
  void note_budget_merge_of(std::size_t i, std::size_t state, bool work_budget) {
    auto at = std::find_if(outcome_.budget_merges.begin(), outcome_.budget_merges.end(),
                           [&](const BudgetMerge& r) { return r.robot == i && r.state == state; });
    if (at == outcome_.budget_merges.end()) at = outcome_.budget_merges.insert(at, BudgetMerge{i, state, false, false});
    (work_budget ? at->work_budget : at->branch_budget) = true;
  }

  void note_blocked(std::size_t i, std::size_t state, double x_m, double y_m, const std::string& why, double mass) {
    for (BlockedRecord& r : outcome_.blocked) {
      if (r.robot == i && r.state == state && r.why == why) {
        r.mass += mass;
        return;
      }
    }
    outcome_.blocked.push_back({i, state, x_m, y_m, why, mass});
  }

  /// Every robot of b that has not finished, as blocked for `why`.
  void note_unfinished(const BranchState& b, const std::string& why) {
    for (std::size_t i = 0; i < b.robots.size(); ++i) {
      const Track& t = b.robots[i];
      if (t.final) continue;
      if (t.stuck_waiting && why == "waiting") {
        note_blocked(i, t.state, t.analysis.blocked_x_m + t.error.mean(0), t.analysis.blocked_y_m + t.error.mean(1),
                     "stuck-waiting", b.weight);
        continue;
      }
      const Eigen::Vector2d p = t.true_mean();
      note_blocked(i, t.state, p.x(), p.y(), why, b.weight);
    }
  }

  void note_race(const BranchState& b, std::vector<std::size_t> robots) {
    std::sort(robots.begin(), robots.end());
    robots.erase(std::unique(robots.begin(), robots.end()), robots.end());
    if (robots.size() < 3) return;
    RaceRecord r;
    r.robots = robots;
    for (const std::size_t i : robots) r.states.push_back(b.robots[i].state);
    for (const RaceRecord& seen : outcome_.races) {
      if (seen.robots == r.robots && seen.states == r.states) return;
    }
    outcome_.races.push_back(std::move(r));
  }

  /// Robot i has just entered `state`: if it drives a leg, every teammate
  /// driving one at the same time is noted (each evaluation ignores the other).
  void note_concurrent_legs(const BranchState& b, std::size_t i, std::size_t state) {
    const auto* mine = std::get_if<mission::GoToGuardedParams>(&mission_.robots[i].states[state].behavior);
    if (mine == nullptr) return;
    const Eigen::Vector2d from = b.robots[i].true_mean();
    for (std::size_t j = 0; j < b.robots.size(); ++j) {
      if (j == i || b.robots[j].final || (entering_ != kNone && j > entering_)) continue;
      const std::size_t js = b.robots[j].state;
      const auto* theirs = std::get_if<mission::GoToGuardedParams>(&mission_.robots[j].states[js].behavior);
      if (theirs == nullptr) continue;
      if (!legs_seen_.insert({i, state, j, js}).second) continue;
      const Eigen::Vector2d at = b.robots[j].true_mean();
      outcome_.concurrent_legs.push_back({i, state, j, js, from.x(), from.y(), mine->goal.x_m, mine->goal.y_m, at.x(),
                                          at.y(), theirs->goal.x_m, theirs->goal.y_m});
    }
  }

  /// Robot i has just entered `state`: if it drives a leg, where from and
  /// with what odometry error, for the trap check on the error's tails. A few
  /// distinct entries per state (branches mostly repeat one another).
  void note_leg_entry(const Track& t, std::size_t i, std::size_t state) {
    if (!std::holds_alternative<mission::GoToGuardedParams>(mission_.robots[i].states[state].behavior)) return;
    constexpr std::size_t kMaxPerState = 8;
    constexpr double kSameM = 0.05, kSameRad = 0.01;
    Eigen::Matrix3d cov = t.error.cov;
    cov.topLeftCorner<2, 2>() += t.extra_cov;
    std::vector<std::size_t>& kept = leg_entries_of_[{i, state}];
    for (const std::size_t k : kept) {
      const LegEntryRecord& seen = outcome_.leg_entries[k];
      const bool same = std::hypot(seen.x0_m - t.base.x_m, seen.y0_m - t.base.y_m) < kSameM &&
                        (seen.error_mean - t.error.mean).head<2>().norm() < kSameM &&
                        std::abs(seen.error_mean(2) - t.error.mean(2)) < kSameRad &&
                        std::abs(std::sqrt(seen.error_cov(2, 2)) - std::sqrt(cov(2, 2))) < kSameRad &&
                        std::abs(std::sqrt(seen.error_cov.topLeftCorner<2, 2>().trace()) -
                                 std::sqrt(cov.topLeftCorner<2, 2>().trace())) < kSameM;
      if (same) return;
    }
    const LegEntryRecord entry{i, state, t.base.x_m, t.base.y_m, t.error.mean, cov};
    if (kept.size() < kMaxPerState) {
      kept.push_back(outcome_.leg_entries.size());
      outcome_.leg_entries.push_back(entry);
      return;
    }
    // Full (a loop's laps gather more error each time round): the entry
    // that strays least gives way, so the widest errors are the ones tried.
    const auto strays = [](const LegEntryRecord& e) {
      constexpr double kLeverM = 10.0;  // a heading error counted over a typical leg
      return e.error_mean.head<2>().norm() + 2.0 * std::sqrt(e.error_cov.topLeftCorner<2, 2>().trace()) +
             kLeverM * (std::abs(e.error_mean(2)) + 2.0 * std::sqrt(e.error_cov(2, 2)));
    };
    const auto least = std::min_element(kept.begin(), kept.end(), [&](std::size_t a, std::size_t b) {
      return strays(outcome_.leg_entries[a]) < strays(outcome_.leg_entries[b]);
    });
    if (strays(outcome_.leg_entries[*least]) < strays(entry)) outcome_.leg_entries[*least] = entry;
  }

  const mission::Mission& mission_;
  const Models& models_;
  std::vector<Segment> walls_;
  std::vector<const RobotModel*> robot_models_;
  SystemOutcome outcome_;
  bool record_entries_ = false;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t entering_ = kNone;
  std::map<std::tuple<std::size_t, std::size_t, double, double, double>, std::shared_ptr<const StateAnalysis>>
      look_ahead_cache_;  ///< look_ahead's predictions
  std::set<std::tuple<std::size_t, std::size_t, std::size_t, std::size_t>> legs_seen_;  ///< concurrent_legs' keys  ///< while the initial states are entered: the robot entering
  std::map<std::pair<std::size_t, std::size_t>, ErrorState> entry_errors_;
  /// outcome_.leg_entries' indices per (robot, state).
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> leg_entries_of_;
  static constexpr std::size_t kMaxCachedAnalyses = 2048;
  std::map<std::string, StateAnalysis> analysis_cache_;
  /// An analysis made, by robot and state: where it began and its entry in
  /// analysis_cache_ (map entries stay put; cached_analysis's reuse under
  /// work pressure picks the nearest).
  struct MadeAnalysis {
    BaseState start;
    std::map<std::string, StateAnalysis>::const_iterator analysis;
  };
  std::map<std::pair<std::size_t, std::size_t>, std::vector<MadeAnalysis>> analyses_made_;
  static constexpr double kWorkPressureAt = 0.5;       ///< share of max_work_cycles spent
  static constexpr double kHeadingMetresPerRad = 0.3;  ///< a radian of entry heading counts as 0.3 m of place
};

}  // namespace

SystemOutcome run_sequence(const mission::Mission& mission, const Models& models, const TeamSnapshot* from) {
  Sequencer sequencer(mission, models);
  return sequencer.run(from);
}

}  // namespace p3at::verifier::engine
