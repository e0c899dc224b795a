#include "p3at/verifier/approximations.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <set>
#include <tuple>
#include <variant>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_document.hpp"

namespace p3at::verifier {
namespace {

using mission::BehaviorKind;
using mission::RobotSpec;

struct P {
  double x = 0.0, y = 0.0;
};
P operator-(P a, P b) { return {a.x - b.x, a.y - b.y}; }
P operator+(P a, P b) { return {a.x + b.x, a.y + b.y}; }
P operator*(double k, P a) { return {k * a.x, k * a.y}; }
double dot(P a, P b) { return a.x * b.x + a.y * b.y; }
double cross(P a, P b) { return a.x * b.y - a.y * b.x; }
double norm(P a) { return std::hypot(a.x, a.y); }

/// The point of segment ab closest to p.
P closest_on(P a, P b, P p) {
  const P d = b - a;
  const double len2 = dot(d, d);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return a + t * d;
}

bool segments_cross(P a, P b, P c, P d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0)) && d1 != 0.0 && d2 != 0.0 && d3 != 0.0 && d4 != 0.0;
}

double segment_distance(P a, P b, P c, P d) {
  if (segments_cross(a, b, c, d)) return 0.0;
  return std::min({norm(closest_on(a, b, c) - c), norm(closest_on(a, b, d) - d), norm(closest_on(c, d, a) - a),
                   norm(closest_on(c, d, b) - b)});
}

std::string num(double v, int decimals) { return format_fixed(v, decimals); }
std::string pt(P p) { return "(" + format_fixed(p.x, 2) + ", " + format_fixed(p.y, 2) + ")"; }

/// Where a robot may be when it enters each state: the start for the
/// initial state; a GoToGuarded's goal after its AtGoal; anywhere on the leg
/// (both ends kept) after any other exit from a GoToGuarded; else where the
/// previous state was entered. A few points per state are enough for leg
/// lengths and geometry.
std::vector<std::vector<P>> entry_points(const RobotSpec& r) {
  std::vector<std::vector<P>> entries(r.states.size());
  const auto add = [&](std::size_t s, P p) {
    for (const P& q : entries[s]) {
      if (norm(q - p) < 0.01) return false;
    }
    if (entries[s].size() >= 16) return false;
    entries[s].push_back(p);
    return true;
  };
  add(r.initial, {r.start.x_m, r.start.y_m});
  for (bool changed = true; changed;) {
    changed = false;
    for (const mission::Transition& t : r.transitions) {
      const auto* go = std::get_if<mission::GoToGuardedParams>(&r.states[t.from].behavior);
      std::vector<P> reach;
      if (go != nullptr) {
        reach.push_back({go->goal.x_m, go->goal.y_m});
        if (t.kind() != mission::TriggerKind::at_goal) reach.insert(reach.end(), entries[t.from].begin(), entries[t.from].end());
      } else {
        reach = entries[t.from];
      }
      for (const P& p : reach) changed = add(t.to, p) || changed;
    }
  }
  return entries;
}

/// The robot's legs of state s (entry point -> goal); empty if not a GoToGuarded.
std::vector<std::pair<P, P>> legs_of(const RobotSpec& r, std::size_t s, const std::vector<std::vector<P>>& entries) {
  std::vector<std::pair<P, P>> legs;
  const auto* go = std::get_if<mission::GoToGuardedParams>(&r.states[s].behavior);
  if (go == nullptr) return legs;
  for (const P& e : entries[s]) legs.push_back({e, {go->goal.x_m, go->goal.y_m}});
  return legs;
}

constexpr std::size_t kNoObject = static_cast<std::size_t>(-1);

/// For each wall, the small object it belongs to (walls joined end to end
/// into a group whose bounding box is under 3 m across: a pillar, a
/// cabinet), or kNoObject (a room's or a hallway's walls).
std::vector<std::size_t> small_objects(const std::vector<Wall>& walls) {
  const std::size_t n = walls.size();
  std::vector<std::size_t> group(n);
  for (std::size_t i = 0; i < n; ++i) group[i] = i;
  const std::function<std::size_t(std::size_t)> root = [&](std::size_t i) {
    return group[i] == i ? i : group[i] = root(group[i]);
  };
  const auto ends = [](const Wall& w) { return std::array<P, 2>{P{w.x0_m, w.y0_m}, P{w.x1_m, w.y1_m}}; };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (const P& a : ends(walls[i])) {
        for (const P& b : ends(walls[j])) {
          if (norm(a - b) < 1e-3) group[root(i)] = root(j);
        }
      }
    }
  }
  std::vector<std::size_t> out(n, kNoObject);
  for (std::size_t i = 0; i < n; ++i) {
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    for (std::size_t j = 0; j < n; ++j) {
      if (root(j) != root(i)) continue;
      for (const P& a : ends(walls[j])) {
        lo_x = std::min(lo_x, a.x);
        lo_y = std::min(lo_y, a.y);
        hi_x = std::max(hi_x, a.x);
        hi_y = std::max(hi_y, a.y);
      }
    }
    if (std::hypot(hi_x - lo_x, hi_y - lo_y) < 3.0) out[i] = root(i);
  }
  return out;
}

class Detector {
 public:
  Detector(const mission::Mission& m, const Models& models, const SystemOutcome& o) : m_(m), models_(models), o_(o) {}

  std::vector<Approximation> run() {
    for (std::size_t i = 0; i < m_.robots.size(); ++i) {
      const RobotSpec& r = m_.robots[i];
      const RobotModel* model = models_.find_robot(r.name);
      if (model == nullptr) continue;
      const auto entries = entry_points(r);
      speed(i, *model);
      noise(i, *model, entries);
      interruptions_and_coupling(i);
      loops(i);
      traps(i, *model, entries);
    }
    races();
    concurrent_legs();
    budget_merges();
    std::stable_sort(out_.begin(), out_.end(), [](const Approximation& a, const Approximation& b) {
      return std::tie(a.robot, a.kind, a.index) < std::tie(b.robot, b.kind, b.index);
    });
    return std::move(out_);
  }

 private:
  void add(ApproximationKind kind, std::size_t robot, MissionElement element, std::size_t index, std::string detail) {
    const RobotSpec& r = m_.robots[robot];
    Approximation a;
    a.kind = kind;
    a.robot = robot;
    a.robot_name = r.name;
    a.element = element;
    a.index = index;
    if (element == MissionElement::state) a.state = r.states[index].name;
    if (element == MissionElement::transition) a.state = r.states[r.transitions[index].from].name;
    for (const Approximation& seen : out_) {
      if (seen.kind == kind && seen.robot == robot && seen.element == element && seen.index == index) return;
    }
    a.detail = std::move(detail);
    a.measured_error = approximation_row(kind).measured;
    a.vouched = vouched(kind);
    out_.push_back(std::move(a));
  }

  void speed(std::size_t i, const RobotModel& model) {
    const RobotSpec& r = m_.robots[i];
    const Kinematics& k = model.kinematics;
    if (k.top_speed_mps > 0.0 && r.max_speed_mps > k.top_speed_mps + 1e-9) {
      add(ApproximationKind::speed_above_top, i, MissionElement::max_speed, 0,
          "max_speed_mps " + num(r.max_speed_mps, 2) + " is above the robot's top speed " +
              num(k.top_speed_mps, 2) + " m/s (models file): it cannot drive that fast, the prediction is optimistic");
    }
    if (!(k.calibrated_speed_mps > 0.0)) {
      add(ApproximationKind::speed_calibration_unknown, i, MissionElement::max_speed, 0,
          "the models file does not record the speed '" + r.name +
              "' was calibrated at (kinematics.calibrated_speed_mps; `vipars calibrate` writes it): max_speed_mps " +
              num(r.max_speed_mps, 2) + " cannot be checked against it");
    } else if (r.max_speed_mps > 1.05 * k.calibrated_speed_mps) {
      add(ApproximationKind::speed_above_calibration, i, MissionElement::max_speed, 0,
          "max_speed_mps " + num(r.max_speed_mps, 2) + " is above the speed the model was calibrated at (" +
              num(k.calibrated_speed_mps, 2) + " m/s): its motion errors are extrapolated");
    }
  }

  void noise(std::size_t i, const RobotModel& model, const std::vector<std::vector<P>>& entries) {
    const RobotSpec& r = m_.robots[i];
    const double speed = std::max(1e-3, r.max_speed_mps);
    for (std::size_t s = 0; s < r.states.size(); ++s) {
      const auto* go = std::get_if<mission::GoToGuardedParams>(&r.states[s].behavior);
      if (go == nullptr) continue;
      double longest = 0.0;
      for (const auto& [from, to] : legs_of(r, s, entries)) longest = std::max(longest, norm(to - from));
      // Cycles to drive the leg at full speed: a lower bound of the leg's real duration.
      const double cycles = longest / speed / model.kinematics.cycle_s;
      if (go->noise_gain == 0.0) continue;
      if (static_cast<double>(go->noise_persistence_cycles) >= cycles) continue;
      // Inside the dropoff the pull toward the goal is move_gain (d - dz) /
      // (dropoff - dz); where it falls below NOISE's gain, a draw pointing
      // away holds the robot there until the next redraw. When that is
      // outside an AtGoal circle of the state, the leg's duration is a tail
      // of redraws, which the redrawn quadrature was measured to miss (fresh
      // gen_7686: gain 0.14, dropoff 0.9 m, AtGoal 0.1 m, held 125 cycles:
      // verify 0.804 against 1,000 runs' 0.732 at 60 s and 0.36 m, a GO
      // against the threshold 0.8 where the runs say NO-GO).
      const double dz = std::max(0.0, go->dead_zone_m);
      const double hold_m =
          go->move_gain > 0.0 ? dz + std::abs(go->noise_gain) / go->move_gain * std::max(0.0, go->dropoff_m - dz)
                              : std::numeric_limits<double>::infinity();
      double circle_m = std::numeric_limits<double>::infinity();
      for (const std::size_t t : r.states[s].outgoing) {
        if (const auto* g = std::get_if<mission::AtGoalParams>(&r.transitions[t].trigger)) {
          circle_m = std::min(circle_m, g->radius_m);
        }
      }
      const bool holds_off = hold_m > circle_m;
      const bool strong = go->dropoff_m >= 1.0 || std::abs(go->noise_gain) > 0.15 || holds_off;
      add(strong ? ApproximationKind::noise_redrawn_strong : ApproximationKind::noise_redrawn_in_leg, i,
          MissionElement::state, s,
          "NOISE redrawn every " + num(static_cast<double>(go->noise_persistence_cycles), 0) +
              " cycles on a leg of up to " + num(longest, 1) + " m (at least " + num(cycles, 0) +
              " cycles at " + num(speed, 2) + " m/s), gain " + num(go->noise_gain, 2) + ", dropoff " +
              num(go->dropoff_m, 2) + " m" +
              (holds_off ? ", which can hold the robot " + num(hold_m, 2) + " m from its goal, outside its " +
                               num(circle_m, 2) + " m AtGoal circle"
                         : "") +
              (go->noise_persistence_cycles == 10 ? " (10 cycles is the format's default)" : ""));
    }
  }

  static bool moving(const RobotSpec& r, std::size_t s) {
    const BehaviorKind k = r.states[s].kind();
    return k == BehaviorKind::go_to_guarded || k == BehaviorKind::spin;
  }

  void interruptions_and_coupling(std::size_t i) {
    const RobotSpec& r = m_.robots[i];
    for (std::size_t t = 0; t < r.transitions.size(); ++t) {
      const mission::Transition& tr = r.transitions[t];
      if (tr.kind() == mission::TriggerKind::notified && r.states[tr.to].kind() == BehaviorKind::go_to_guarded) {
        add(ApproximationKind::leg_entered_on_message, i, MissionElement::state, tr.to,
            "entered on '" + std::get<mission::NotifiedParams>(tr.trigger).message +
                "': where within a cycle the leg starts is not modelled, which shifts its end by millimetres and "
                "its duration by a cycle; the decision is taken at Tmax - " + num(kWidenTime_s, 1) + " s, Rmax - " +
                num(kWidenRadius_m, 2) + " m");
      }
      if (tr.kind() != mission::TriggerKind::notified || !moving(r, tr.from)) continue;
      const auto& msg = std::get<mission::NotifiedParams>(tr.trigger).message;
      add(ApproximationKind::message_interrupts_motion, i, MissionElement::transition, t,
          "'" + msg + "' can interrupt " + std::string(mission::to_string(r.states[tr.from].kind())) + " state '" +
              r.states[tr.from].name +
              "' mid-motion: the model places the robot along its paths at 12 bins of the message's time "
              "(docs/verifier.md), measured outside the bounds on patrol_recall");
      // Where the robot ends then depends on when the message came: if a final
      // state follows without another leg to a fixed goal, the final position
      // and the completion time are coupled.
      if (reaches_final_without_leg(r, tr.to)) {
        add(ApproximationKind::time_position_coupled, i, MissionElement::transition, t,
            "after '" + msg + "' interrupts '" + r.states[tr.from].name +
                "', the robot's final position depends on when the message came; the joint P(t <= Tmax and r <= "
                "Rmax) is computed as if they were independent");
      }
    }
  }

  static bool reaches_final_without_leg(const RobotSpec& r, std::size_t from) {
    std::vector<bool> seen(r.states.size(), false);
    std::vector<std::size_t> todo{from};
    while (!todo.empty()) {
      const std::size_t s = todo.back();
      todo.pop_back();
      if (seen[s]) continue;
      seen[s] = true;
      if (r.is_final(s)) return true;
      if (r.states[s].kind() == BehaviorKind::go_to_guarded) continue;  // a leg to a fixed goal decouples
      for (const std::size_t t : r.states[s].outgoing) todo.push_back(r.transitions[t].to);
    }
    return false;
  }

  void loops(std::size_t i) {
    const RobotSpec& r = m_.robots[i];
    std::vector<int> mark(r.states.size(), 0);  // 0 new, 1 on the stack, 2 done
    std::function<void(std::size_t)> dfs = [&](std::size_t s) {
      mark[s] = 1;
      for (const std::size_t t : r.states[s].outgoing) {
        const std::size_t to = r.transitions[t].to;
        if (mark[to] == 1) {
          add(ApproximationKind::fsa_loop, i, MissionElement::transition, t,
              "transition '" + r.states[s].name + "' -> '" + r.states[to].name +
                  "' closes a loop: the model evaluates it lap by lap, each lap racing its exits, up to its "
                  "budget (the laps beyond it count as failure), measured outside the bounds on patrol_recall");
        } else if (mark[to] == 0) {
          dfs(to);
        }
      }
      mark[s] = 2;
    };
    dfs(r.initial);
  }

  /// What may pin a robot driving from a to b: a wall across the leg, a
  /// concave corner within AVOID's reach of it, a gap narrower than the robot
  /// with margin that it passes through. `body` is the robot's radius plus
  /// the margin, `reach` AVOID_OBSTACLES' influence, `narrow` the widest gap
  /// counted as one.
  static void leg_traps(P a, P b, const std::vector<Wall>& walls, const std::vector<std::size_t>& part, double body,
                        double reach, double narrow, std::vector<std::string>& found) {
    // Only walls within reach of the leg can pin the robot on it: every
    // test below needs both of its walls that close (this keeps the cost
    // linear in the walls for a large map).
    std::vector<std::size_t> near;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const P c{walls[w].x0_m, walls[w].y0_m}, d{walls[w].x1_m, walls[w].y1_m};
      if (segment_distance(a, b, c, d) < std::max(reach, narrow)) near.push_back(w);
    }
    for (std::size_t ni = 0; ni < near.size(); ++ni) {
      const std::size_t w = near[ni];
      const P c{walls[w].x0_m, walls[w].y0_m}, d{walls[w].x1_m, walls[w].y1_m};
      if (segments_cross(a, b, c, d)) found.push_back("a wall " + pt(c) + "-" + pt(d) + " lies across the leg");
      for (std::size_t nj = ni + 1; nj < near.size(); ++nj) {
        const std::size_t v = near[nj];
        const P e{walls[v].x0_m, walls[v].y0_m}, f{walls[v].x1_m, walls[v].y1_m};
        // A concave corner: two walls meeting at a point, the leg passing
        // inside the angle they make within AVOID's reach of both (where
        // their pushes and the goal's pull can cancel: a robot pinned).
        for (const auto& [corner, u_end] : {std::pair{c, d}, std::pair{d, c}}) {
          for (const auto& [other_corner, other_end] : {std::pair{e, f}, std::pair{f, e}}) {
            if (norm(corner - other_corner) > 1e-3) continue;
            const P u = u_end - corner, vv = other_end - corner;
            const double det = cross(u, vv);
            if (std::abs(det) < 1e-6 * norm(u) * norm(vv)) continue;  // collinear: one straight wall
            const double length = norm(b - a);
            const int steps = std::max(1, static_cast<int>(length / 0.1));
            for (int k = 0; k <= steps; ++k) {
              const P q = a + (static_cast<double>(k) / steps) * (b - a);
              const P rel = q - corner;
              const double alpha = cross(rel, vv) / det, beta = cross(u, rel) / det;
              if (!(alpha > 0.0 && beta > 0.0)) continue;
              if (norm(closest_on(c, d, q) - q) < reach && norm(closest_on(e, f, q) - q) < reach) {
                found.push_back("a concave corner at " + pt(corner) + ": the leg passes within " + num(reach, 2) +
                                " m (avoidance reach) of both its walls");
                break;
              }
            }
          }
        }
        // A narrow gap between two walls that the leg passes through
        // (not two sides of one small object, such as a pillar's).
        const double gap = segment_distance(c, d, e, f);
        if (gap > 1e-3 && gap < narrow && !(part[w] == part[v] && part[w] != kNoObject)) {
          P p1 = closest_on(c, d, closest_on(e, f, c)), p2 = closest_on(e, f, p1);
          for (const P& cand : {c, d}) {
            const P q = closest_on(e, f, cand);
            if (norm(q - cand) < norm(p2 - p1)) {
              p1 = cand;
              p2 = q;
            }
          }
          if (segments_cross(a, b, p1, p2) || norm(closest_on(a, b, 0.5 * (p1 + p2)) - 0.5 * (p1 + p2)) < 0.5 * gap) {
            found.push_back("a gap of " + num(gap, 2) + " m between walls at " + pt(0.5 * (p1 + p2)) +
                            " (the robot needs " + num(2.0 * body, 2) + " m plus margin)");
          }
        }
      }
    }
  }

  /// The paths a run may drive instead of the believed leg from e's start to
  /// `goal`, as polylines: the mean path (the leg moved by the predicted mean
  /// pose error: its start by the position error, turned by the heading
  /// error, bent by the heading drift the leg gathers), and that path moved
  /// kTailSds standard deviations of the sideways error to either side at
  /// every point. The sideways error at distance s along the leg is a.e for
  /// the entry's error e, a = (across, s), plus what the leg gathers itself
  /// (heading variance h per metre: h s^3 / 3), so the band widens along the
  /// leg the way a run's spread does.
  static std::vector<std::vector<P>> run_paths(const LegEntryRecord& e, P goal, const MotionError& motion) {
    constexpr int kPieces = 8;
    const P from{e.x0_m, e.y0_m};
    const P d = goal - from;
    const double length = norm(d);
    const double c = std::cos(e.error_mean(2)), sn = std::sin(e.error_mean(2));
    const P along = length > 1e-9 ? (1.0 / length) * P{c * d.x - sn * d.y, sn * d.x + c * d.y} : P{1.0, 0.0};
    const P left{-along.y, along.x};
    const Eigen::Vector3d across(-d.y / std::max(length, 1e-9), d.x / std::max(length, 1e-9), 0.0);
    std::vector<std::vector<P>> paths(3);
    for (int k = 0; k <= kPieces; ++k) {
      const double s = length * k / kPieces;
      const P mean = from + P{e.error_mean(0), e.error_mean(1)} + s * along +
                     (motion.drift_rad_per_m * s * s / 2.0) * left;
      const Eigen::Vector3d a(across(0), across(1), s);
      const double sd = std::sqrt(std::max(0.0, a.dot(e.error_cov * a)) + motion.heading_var_per_m * s * s * s / 3.0);
      paths[0].push_back(mean);
      paths[1].push_back(mean + (kTailSds * sd) * left);
      paths[2].push_back(mean - (kTailSds * sd) * left);
    }
    return paths;
  }
  static constexpr double kTailSds = 2.0;

  void traps(std::size_t i, const RobotModel& model, const std::vector<std::vector<P>>& entries) {
    const RobotSpec& r = m_.robots[i];
    const auto& walls = models_.environment.walls;
    const std::vector<std::size_t> part = small_objects(walls);
    for (std::size_t s = 0; s < r.states.size(); ++s) {
      const auto* go = std::get_if<mission::GoToGuardedParams>(&r.states[s].behavior);
      if (go == nullptr) continue;
      const double body = model.kinematics.robot_radius_m + go->safety_margin_m;
      const double reach = body + go->sphere_m;  // AVOID_OBSTACLES' influence
      const double narrow = 2.0 * body + 0.2;    // a gap the robot cannot pass with margin
      std::vector<std::string> found;
      for (const auto& [a, b] : legs_of(r, s, entries)) leg_traps(a, b, walls, part, body, reach, narrow, found);
      // The mission's legs are where the robot believes it drives; a run
      // drives them moved by the pose error it has gathered, which the
      // evaluation predicts at each entry (gen_7082: robot1's fourth leg
      // crosses a 2.15 m doorway in its middle as written, and 15 % of the
      // runs ended pinned on the doorway's wall after three legs and a spin).
      if (found.empty()) {
        for (const LegEntryRecord& e : o_.leg_entries) {
          if (e.robot != i || e.state != s) continue;
          for (const std::vector<P>& path : run_paths(e, {go->goal.x_m, go->goal.y_m}, model.motion)) {
            for (std::size_t k = 1; k < path.size(); ++k) {
              leg_traps(path[k - 1], path[k], walls, part, body, reach, narrow, found);
            }
          }
        }
        for (std::string& f : found) {
          f = "with the pose error a run may carry (the predicted mean, and " + num(kTailSds, 0) +
              " sd either side along the leg): " + f;
        }
      }
      if (found.empty()) continue;
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      std::string detail = found.front();
      if (found.size() > 1) detail += " (and " + std::to_string(found.size() - 1) + " more)";
      add(ApproximationKind::may_get_trapped, i, MissionElement::state, s,
          detail + ": the robot may be pinned; the model's paths say whether each quadrature direction gets stuck, "
                   "not how often a real run escapes");
    }
  }

  void races() {
    for (const RaceRecord& race : o_.races) {
      std::string who;
      for (std::size_t k = 0; k < race.robots.size(); ++k) {
        who += (k ? ", " : "") + m_.robots[race.robots[k]].name + " in '" +
               m_.robots[race.robots[k]].states[race.states[k]].name + "'";
      }
      for (std::size_t k = 0; k < race.robots.size(); ++k) {
        add(ApproximationKind::robots_racing, race.robots[k], MissionElement::state, race.states[k],
            std::to_string(race.robots.size()) + " robots may each act first (" + who +
                "): the order's probability is a product of pairwise ones");
      }
    }
  }

  void concurrent_legs() {
    for (const ConcurrentLegs& c : o_.concurrent_legs) {
      const RobotSpec& r = m_.robots[c.robot];
      const RobotSpec& t = m_.robots[c.teammate];
      const RobotModel* mr = models_.find_robot(r.name);
      const RobotModel* mt = models_.find_robot(t.name);
      const auto* go = std::get_if<mission::GoToGuardedParams>(&r.states[c.state].behavior);
      if (mr == nullptr || mt == nullptr || go == nullptr) continue;
      const double reach = mr->kinematics.robot_radius_m + mt->kinematics.robot_radius_m + go->safety_margin_m + go->sphere_m;
      const P a{c.x0_m, c.y0_m}, b{c.x1_m, c.y1_m}, e{c.tx0_m, c.ty0_m}, f{c.tx1_m, c.ty1_m};
      const double d = segment_distance(a, b, e, f);
      if (d >= reach) continue;
      const std::string how = d == 0.0 ? "crosses" : "comes within " + num(d, 2) + " m of";
      add(ApproximationKind::teammates_moving_near_path, c.robot, MissionElement::state, c.state,
          "its leg " + pt(a) + "-" + pt(b) + " " + how + " " + t.name + "'s leg in '" + t.states[c.teammate_state].name +
              "' " + pt(e) + "-" + pt(f) + ", driven at the same time (avoidance reach " + num(reach, 2) +
              " m): neither evaluation sees the other drive (a teammate is an obstacle only where it stands still)");
    }
  }

  void budget_merges() {
    for (const BudgetMerge& b : o_.budget_merges) {
      std::string how;
      if (b.branch_budget) {
        how = "its places (where messages found it) were merged into fewer to keep within the branch budget "
              "(budget.max_branches " + std::to_string(models_.budget.max_branches) + ")";
      }
      if (b.work_budget) {
        how += std::string(how.empty() ? "" : "; ") + "past half of budget.max_work_cycles (" +
               std::to_string(models_.budget.max_work_cycles) +
               "), a leg entered from a new place took the analysis of the nearest place it had been entered from";
      }
      add(ApproximationKind::places_merged_over_budget, b.robot, MissionElement::state, b.state,
          how + " (" + num(o_.budget_merged_mass, 3) + " of the finished mass went through such merges): where it "
          "is, and so its later legs, is pictured more coarsely than the model otherwise does");
    }
  }

  const mission::Mission& m_;
  const Models& models_;
  const SystemOutcome& o_;
  std::vector<Approximation> out_;
};

std::string location(const std::string& file, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0) return file;
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

}  // namespace

const char* to_string(ApproximationKind kind) { return approximation_row(kind).name; }

std::vector<Approximation> detect_approximations(const mission::Mission& mission, const Models& models,
                                                 const SystemOutcome& outcome) {
  return Detector(mission, models, outcome).run();
}

std::vector<Approximation> detect_approximations_before_evaluation(const mission::Mission& mission,
                                                                   const Models& models) {
  // No races and no concurrent legs: races() and concurrent_legs() add nothing.
  const SystemOutcome no_evaluation;
  return Detector(mission, models, no_evaluation).run();
}

bool all_vouched(const std::vector<Approximation>& approximations) {
  return std::all_of(approximations.begin(), approximations.end(), [](const Approximation& a) { return a.vouched; });
}

std::string unvouched_kinds(const std::vector<Approximation>& approximations) {
  std::string out;
  std::set<ApproximationKind> seen;
  for (const Approximation& a : approximations) {
    if (a.vouched || !seen.insert(a.kind).second) continue;
    out += (out.empty() ? "" : ",") + std::string(to_string(a.kind));
  }
  return out;
}

MissionLocator::MissionLocator(std::string_view mission_yaml, std::string mission_file)
    : file_(std::move(mission_file)) {
  try {
    const YAML::Node root = yaml_document::load_single(mission_yaml, "empty");
    const YAML::Node robots = root["robots"];
    if (!robots || !robots.IsSequence()) return;
    for (std::size_t i = 0; i < robots.size(); ++i) {
      const YAML::Node robot = robots[i];
      robots_.push_back(location(file_, robot));
      const YAML::Node speed = robot.IsMap() ? robot["max_speed_mps"] : YAML::Node();
      speeds_.push_back(speed ? location(file_, speed) : robots_.back());
      for (const auto& [key, out] : {std::pair{"states", &states_}, std::pair{"transitions", &transitions_}}) {
        out->emplace_back();
        const YAML::Node list = robot.IsMap() ? robot[key] : YAML::Node();
        if (!list || !list.IsSequence()) continue;
        for (std::size_t k = 0; k < list.size(); ++k) out->back().push_back(location(file_, list[k]));
      }
    }
  } catch (...) {
    // a text that does not parse here: every element is just the file
  }
}

std::string MissionLocator::where(std::size_t robot, MissionElement element, std::size_t index) const {
  if (robot >= robots_.size()) return file_;
  switch (element) {
    case MissionElement::robot: return robots_[robot];
    case MissionElement::max_speed: return speeds_[robot];
    case MissionElement::state: return index < states_[robot].size() ? states_[robot][index] : robots_[robot];
    case MissionElement::transition:
      return index < transitions_[robot].size() ? transitions_[robot][index] : robots_[robot];
  }
  return file_;
}

void locate_approximations(std::vector<Approximation>& approximations, const MissionLocator& locator) {
  for (Approximation& a : approximations) a.where = locator.where(a.robot, a.element, a.index);
}

}  // namespace p3at::verifier
