// The robots' starts, routes and scripts: legs of 1-25 m (mostly 2-10),
// spins, patrols, at each robot's own speed; the shapes people draw on a
// floor plan, checked so that no robot drives through another's resting place.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gen_internal.hpp"

namespace p3at::mission_gen {

double point_segment_distance(Point2 p, const Seg& s) {
  const double dx = s.b.x_m - s.a.x_m, dy = s.b.y_m - s.a.y_m;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x_m - s.a.x_m) * dx + (p.y_m - s.a.y_m) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x_m - (s.a.x_m + t * dx), p.y_m - (s.a.y_m + t * dy));
}

bool segments_cross(const Seg& s, const Seg& t) {
  const auto cross = [](Point2 o, Point2 a, Point2 b) {
    return (a.x_m - o.x_m) * (b.y_m - o.y_m) - (a.y_m - o.y_m) * (b.x_m - o.x_m);
  };
  const double d1 = cross(s.a, s.b, t.a), d2 = cross(s.a, s.b, t.b);
  const double d3 = cross(t.a, t.b, s.a), d4 = cross(t.a, t.b, s.b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

double segment_distance(const Seg& s, const Seg& t) {
  if (segments_cross(s, t)) return 0.0;
  return std::min({point_segment_distance(s.a, t), point_segment_distance(s.b, t), point_segment_distance(t.a, s),
                   point_segment_distance(t.b, s)});
}

std::vector<Seg> route_segments(const RobotPlan& robot) {
  std::vector<Seg> segs;
  Point2 at = robot.start;
  std::vector<Point2> op_start(robot.ops.size() + 1, at);
  for (std::size_t i = 0; i < robot.ops.size(); ++i) {
    op_start[i] = at;
    const Op& op = robot.ops[i];
    if (op.kind == Op::Kind::go) {
      segs.push_back({at, op.goal});
      at = op.goal;
    } else if (op.kind == Op::Kind::patrol) {
      segs.push_back({at, op.goal});
      segs.push_back({op.goal, op.goal2});
      at = op.goal2;  // left from either corner, or from between them
    }
  }
  op_start[robot.ops.size()] = at;
  // A recall leaves a leg part-way and heads for the target's goal directly;
  // a patrol is left from anywhere on its lap.
  const auto next_goal = [&robot](std::size_t from) -> const Point2* {
    for (std::size_t j = from; j < robot.ops.size(); ++j) {
      if (robot.ops[j].kind == Op::Kind::go || robot.ops[j].kind == Op::Kind::patrol) return &robot.ops[j].goal;
    }
    return nullptr;
  };
  for (std::size_t i = 0; i < robot.ops.size(); ++i) {
    const Op& op = robot.ops[i];
    if (op.kind == Op::Kind::patrol) {
      if (const Point2* g = next_goal(i + 1)) {
        segs.push_back({op.goal, *g});
        segs.push_back({Point2{(op.goal.x_m + op.goal2.x_m) / 2, (op.goal.y_m + op.goal2.y_m) / 2}, *g});
      }
    }
    if (op.recall.empty() || op.recall_target < 0) continue;
    if (const Point2* g = next_goal(static_cast<std::size_t>(op.recall_target))) {
      const Point2 a = op_start[i];
      const Point2 b = op.kind == Op::Kind::go ? op.goal : a;
      segs.push_back({Point2{(a.x_m + b.x_m) / 2, (a.y_m + b.y_m) / 2}, *g});
      segs.push_back({a, *g});
    }
  }
  return segs;
}

namespace {

constexpr double kPi = std::numbers::pi;

double leg_length(GenRng& rng) {
  switch (rng.weighted({0.15, 0.7, 0.15})) {
    case 0: return rng.uniform(1.0, 2.0);
    case 1: return rng.uniform(2.0, 10.0);
    default: return rng.uniform(10.0, 25.0);
  }
}

mission::GoToGuardedParams draw_guard(GenRng& rng, double leg_m, double speed_mps) {
  mission::GoToGuardedParams p;
  p.dropoff_m = round_to(rng.uniform(0.3, 2.0), 0.05);
  if (rng.chance(0.2)) p.dead_zone_m = round_to(rng.uniform(0.02, 0.1), 0.01);
  switch (rng.weighted({0.1, 0.9})) {
    case 0: p.noise_gain = 0.0; break;
    default: p.noise_gain = round_to(rng.uniform(0.02, 0.3), 0.005); break;
  }
  const double leg_cycles = std::max(1.0, leg_m / speed_mps / 0.1);
  switch (rng.weighted({0.35, 0.15, 0.15, 0.35})) {
    case 0: p.noise_persistence_cycles = 10; break;  // the format's default
    case 1: p.noise_persistence_cycles = 1; break;   // redrawn every cycle
    case 2: p.noise_persistence_cycles = static_cast<std::int64_t>(std::ceil(leg_cycles * 1.5 / 10) * 10); break;
    default: p.noise_persistence_cycles = static_cast<std::int64_t>(std::round(rng.log_uniform(2.0, std::max(3.0, leg_cycles))));
  }
  if (rng.chance(0.3)) {
    p.sphere_m = round_to(rng.uniform(0.4, 1.0), 0.05);
    p.safety_margin_m = round_to(rng.uniform(0.15, 0.3), 0.05);
  }
  return p;
}

Op go_op(GenRng& rng, Point2 goal, double leg_m, double speed_mps) {
  Op op;
  op.kind = Op::Kind::go;
  op.goal = goal;
  op.go_params = draw_guard(rng, leg_m, speed_mps);
  op.radius_m = std::max(round_to(rng.uniform(0.1, 0.5), 0.05), op.go_params.dead_zone_m + 0.05);
  // Near the goal MOVE_TO_GUARDED pulls with radius/dropoff at most; a NOISE
  // gain above that can hold the robot outside the AtGoal radius for good.
  // People mostly tune that away (9 legs in 10 here); the rest stay, as written.
  const double pull = op.radius_m / op.go_params.dropoff_m;
  if (op.go_params.noise_gain >= 0.8 * pull && rng.chance(0.9)) {
    op.go_params.noise_gain = std::max(0.0, round_to(0.8 * pull * rng.uniform(0.3, 1.0), 0.005));
  }
  return op;
}

Op spin_op(GenRng& rng) {
  Op op;
  op.kind = Op::Kind::spin;
  static const std::vector<double> angles{90, 180, 360, 45, 270};
  op.angle_deg = rng.chance(0.7) ? rng.pick(angles) : round_to(rng.uniform(20, 360), 5);
  // Mostly what a P3-AT can do (43 deg/s); now and then faster than it can turn.
  const double rate = rng.chance(0.9) ? round_to(rng.uniform(15, 43), 1) : round_to(rng.uniform(50, 90), 5);
  op.rate_deg_s = rng.chance(0.5) ? rate : -rate;
  if (rng.chance(0.4)) op.offset_deg = std::min(round_to(rng.uniform(2, 20), 1), op.angle_deg / 3);
  return op;
}

// A point `len` away from `from` in a direction near `heading`, inside the
// team's area; in a hallway, along it in the robot's own lane (people give
// each robot its side of a hallway: head-on robots block each other).
Point2 next_point(GenRng& rng, Point2 from, double& heading, double len, bool corridor, double lane_y, double half_extent) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    Point2 p;
    double h = heading;
    if (corridor) {
      h = rng.chance(0.75) ? heading : heading + kPi;
      p = Point2{round_to(from.x_m + len * std::cos(h), 0.1), round_to(lane_y + rng.uniform(-0.2, 0.2), 0.1)};
    } else {
      const double turn = rng.chance(0.2) ? rng.uniform(-0.5, 0.5) : (rng.chance(0.5) ? 1 : -1) * rng.uniform(0.9, 2.6);
      h = heading + turn;
      p = Point2{round_to(from.x_m + len * std::cos(h), 0.1), round_to(from.y_m + len * std::sin(h), 0.1)};
    }
    const double leg = dist(p, from);  // after rounding: every leg 1-25 m
    if (leg >= 1.0 && leg <= 25.0 && std::abs(p.x_m) <= half_extent + 0.01 && std::abs(p.y_m) <= half_extent + 0.01) {
      heading = corridor ? (std::cos(h) >= 0 ? 0.0 : kPi) : h;
      return p;
    }
  }
  // Cornered: head back toward the middle (at least a metre).
  heading = std::abs(from.x_m) + std::abs(from.y_m) < 1.0 ? 0.0 : std::atan2(corridor ? 0.0 : -from.y_m, -from.x_m);
  const double l = std::max(1.2, std::min(len, std::hypot(from.x_m, corridor ? 0.0 : from.y_m)));
  return Point2{round_to(from.x_m + l * std::cos(heading), 0.1),
                corridor ? lane_y : round_to(from.y_m + l * std::sin(heading), 0.1)};
}

RobotPlan draw_robot(GenRng& rng, std::size_t index, Point2 start, bool corridor, double half_extent) {
  const double lane_y = start.y_m;
  RobotPlan r;
  r.name = "robot" + std::to_string(index + 1);
  r.start = start;
  r.max_speed_mps = rng.chance(0.35) ? 0.3 : round_to(rng.uniform(0.1, kTopSpeedMps), 0.05);
  const std::size_t legs = 1 + rng.weighted({0.25, 0.3, 0.22, 0.13, 0.1});
  double heading = corridor ? (rng.chance(0.5) ? 0.0 : kPi) : rng.uniform(-kPi, kPi);
  Point2 at = start;
  for (std::size_t l = 0; l < legs; ++l) {
    const double len = leg_length(rng);
    const Point2 p = next_point(rng, at, heading, len, corridor, lane_y, half_extent);
    if (dist(p, at) < 1.0) continue;  // cornered into a leg nobody would write
    r.ops.push_back(go_op(rng, p, dist(p, at), r.max_speed_mps));
    at = p;
    if (rng.chance(0.3)) r.ops.push_back(spin_op(rng));
  }
  if (r.ops.empty() || r.ops.back().kind != Op::Kind::go) {
    // Every robot ends with a leg: the goal its radius criterion is measured from.
    double h = heading;
    const Point2 p = next_point(rng, at, h, std::max(2.0, leg_length(rng)), corridor, lane_y, half_extent);
    r.ops.push_back(go_op(rng, p, dist(p, at), r.max_speed_mps));
  }
  const Point2 first = r.ops.front().goal;
  const double toward = std::atan2(first.y_m - start.y_m, first.x_m - start.x_m) * 180 / kPi;
  r.theta_deg = rng.chance(0.8) ? round_to(toward + rng.uniform(-30, 30), 5) : round_to(rng.uniform(-180, 180), 15);
  if (r.theta_deg > 180) r.theta_deg -= 360;
  if (r.theta_deg <= -180) r.theta_deg += 360;
  return r;
}

// The places a robot stands still for a while: where it starts and ends.
std::vector<Point2> resting_points(const RobotPlan& r) {
  std::vector<Point2> pts{r.start};
  for (auto it = r.ops.rbegin(); it != r.ops.rend(); ++it) {
    if (it->kind == Op::Kind::go) {
      pts.push_back(it->goal);
      break;
    }
  }
  return pts;
}

// The goals where a robot must stop (within its AtGoal radius).
std::vector<Point2> goals(const RobotPlan& r) {
  std::vector<Point2> g;
  for (const Op& op : r.ops) {
    if (op.kind == Op::Kind::go) g.push_back(op.goal);
  }
  return g;
}

// Routes pass at least 1.1 m (centre to centre) from where teammates stand
// still; goals are at least 2 m from them (AVOID_OBSTACLES pushes a robot
// within about 1.8 m of a teammate, and it must stop within its radius).
bool keeps_clear(const RobotPlan& r, const std::vector<RobotPlan>& others) {
  const std::vector<Seg> mine = route_segments(r);
  const std::vector<Point2> my_rest = resting_points(r);
  const std::vector<Point2> my_goals = goals(r);
  for (const RobotPlan& o : others) {
    const std::vector<Point2> rest = resting_points(o);
    for (const Point2& p : rest) {
      for (const Seg& s : mine) {
        if (point_segment_distance(p, s) < 1.1) return false;
      }
      for (const Point2& g : my_goals) {
        if (dist(p, g) < 2.0) return false;
      }
    }
    for (const Seg& s : route_segments(o)) {
      for (const Point2& p : my_rest) {
        if (point_segment_distance(p, s) < 1.1) return false;
      }
    }
    for (const Point2& g : goals(o)) {
      for (const Point2& p : my_rest) {
        if (dist(p, g) < 2.0) return false;
      }
    }
  }
  return true;
}

}  // namespace

TeamPlan draw_routes(GenRng& rng, std::size_t robots, bool corridor) {
  TeamPlan team;
  team.corridor = corridor;
  const double half_extent = corridor ? 14.0 : rng.uniform(6.0, 14.0);
  for (std::size_t i = 0; i < robots; ++i) {
    RobotPlan best;
    bool found = false;
    for (int attempt = 0; attempt < 60 && !found; ++attempt) {
      const double spread = 2.0 + 1.2 * static_cast<double>(robots);
      // In a hallway each robot has its lane, 2 m from the next.
      const double lane = (static_cast<double>(i) - static_cast<double>(robots - 1) / 2.0) * 2.0;
      Point2 start{round_to(rng.uniform(-spread, spread), 0.5),
                   corridor ? lane : round_to(rng.uniform(-spread, spread), 0.5)};
      if (corridor) start.x_m = round_to(rng.uniform(-12.0, -12.0 + spread), 0.5);
      bool apart = true;
      for (const RobotPlan& o : team.robots) apart = apart && dist(o.start, start) >= 1.5;
      if (!apart) continue;
      RobotPlan r = draw_robot(rng, i, start, corridor, half_extent);
      best = r;
      found = keeps_clear(r, team.robots);
    }
    team.robots.push_back(best);  // after 60 tries, a route that passes close: people write those too
  }
  return team;
}

double nominal_time_s(const TeamPlan& team) {
  // Each robot's script at its own speed; a wait or a patrol ends when the
  // awaited message is sent (its sender comes earlier in team.order).
  std::vector<double> sent_at(team.messages.size(), 0.0);
  const auto message_time = [&team, &sent_at](const std::string& name) {
    for (std::size_t m = 0; m < team.messages.size(); ++m) {
      if (team.messages[m].name == name) return sent_at[m];
    }
    return 0.0;
  };
  double finish = 0.0;
  for (std::size_t k : team.order) {
    const RobotPlan& r = team.robots[k];
    double t = 0.0;
    Point2 at = r.start;
    for (const Op& op : r.ops) {
      switch (op.kind) {
        case Op::Kind::go: {
          const double d = dist(at, op.goal);
          t += d / r.max_speed_mps + op.go_params.dropoff_m / r.max_speed_mps + r.max_speed_mps / 0.3 + 0.5;
          at = op.goal;
          break;
        }
        case Op::Kind::spin:
          t += (op.angle_deg - op.offset_deg) / std::min(std::abs(op.rate_deg_s), 43.0) + 0.5;
          break;
        case Op::Kind::notify:
          for (std::size_t m = 0; m < team.messages.size(); ++m) {
            if (team.messages[m].name == op.message) sent_at[m] = t;
          }
          t += 0.2;
          break;
        case Op::Kind::wait:
          t = std::max(t, message_time(op.message) + 0.1);
          break;
        case Op::Kind::patrol:
          t += dist(at, op.goal) / r.max_speed_mps;
          t = std::max(t, message_time(op.message) + 0.1);
          at = op.goal;
          break;
      }
    }
    finish = std::max(finish, t);
  }
  return finish;
}

}  // namespace p3at::mission_gen
