// The world around the routes: a room (or a hallway) just larger than the
// team's routes, with doorways where routes cross an inner wall, alcoves in
// the outer walls beside a route, pillars and free-standing walls near the
// routes but never on them; and the "real world" the verifier never reads:
// each robot's wheel-scale and track errors, random odometry errors of
// different sizes, a radio that is sometimes slow and sometimes loses packets.

#include <algorithm>
#include <cmath>
#include <limits>

#include "gen_internal.hpp"

namespace p3at::mission_gen {
namespace {

struct Room {
  double x0, y0, x1, y1;
};

// Where walls may not go: within `keep` of a route (the robot's centre passes
// there), or within kStopClearance of a goal or a start (the robot must stop
// there, within an AtGoal radius of a few decimetres, and AVOID_OBSTACLES
// pushes within sphere + safety margin, 1.25 m by default, of a wall's surface).
constexpr double kStopClearance = 1.6;

struct Keepout {
  std::vector<Seg> routes;
  std::vector<Point2> stops;  ///< starts and goals
};

bool point_clear(Point2 p, const Keepout& k, double keep) {
  for (const Seg& s : k.routes) {
    if (point_segment_distance(p, s) < keep) return false;
  }
  for (const Point2& s : k.stops) {
    if (dist(p, s) < kStopClearance) return false;
  }
  return true;
}

bool seg_clear(const Seg& w, const Keepout& k, double keep) {
  for (const Seg& s : k.routes) {
    if (segment_distance(w, s) < keep) return false;
  }
  for (const Point2& s : k.stops) {
    if (point_segment_distance(s, w) < kStopClearance) return false;
  }
  return true;
}

// A straight wall from a to b, cut wherever a route or start passes within
// `keep` of it: the cuts are its doorways. Returns the pieces; `gaps` counts
// the openings between pieces or between a piece and the line's ends.
std::vector<Seg> wall_with_doorways(Point2 a, Point2 b, double keep, const Keepout& keepout, std::size_t& gaps) {
  const double len = dist(a, b);
  const int steps = std::max(2, static_cast<int>(len / 0.05));
  std::vector<bool> solid(static_cast<std::size_t>(steps) + 1);
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const Point2 p{a.x_m + t * (b.x_m - a.x_m), a.y_m + t * (b.y_m - a.y_m)};
    solid[static_cast<std::size_t>(i)] = point_clear(p, keepout, keep);
  }
  // A gap narrower than 0.6 m is no doorway (a P3-AT is 0.5 m wide): the
  // wall runs through it, a hair inside the goal clearance that made it.
  const int min_gap = static_cast<int>(std::ceil(0.6 / (len / steps)));
  for (int i = 1; i <= steps; ++i) {
    if (solid[static_cast<std::size_t>(i)] || !solid[static_cast<std::size_t>(i - 1)]) continue;
    int j = i;
    while (j <= steps && !solid[static_cast<std::size_t>(j)]) ++j;
    if (j <= steps && j - i < min_gap) {
      for (int k = i; k < j; ++k) solid[static_cast<std::size_t>(k)] = true;
    }
    i = j;
  }
  std::vector<Seg> pieces;
  gaps = 0;
  bool in_gap = false;
  int begin = -1;
  for (int i = 0; i <= steps + 1; ++i) {
    const bool s = i <= steps && solid[static_cast<std::size_t>(i)];
    if (s && begin < 0) begin = i;
    if (!s && begin >= 0) {
      const double t0 = static_cast<double>(begin) / steps, t1 = static_cast<double>(i - 1) / steps;
      if ((t1 - t0) * len >= 0.3) {
        const auto at = [&](double t) {
          return Point2{round_to(a.x_m + t * (b.x_m - a.x_m), 0.05), round_to(a.y_m + t * (b.y_m - a.y_m), 0.05)};
        };
        pieces.push_back({at(t0), at(t1)});
      }
      begin = -1;
    }
    if (i <= steps) {
      if (!s && !in_gap) ++gaps;
      in_gap = !s;
    }
  }
  return pieces;
}

bool inside(const Room& r, Point2 p, double margin) {
  return p.x_m > r.x0 + margin && p.x_m < r.x1 - margin && p.y_m > r.y0 + margin && p.y_m < r.y1 - margin;
}

}  // namespace

WorldPlan draw_world(GenRng& rng, const TeamPlan& team, int layout) {
  WorldPlan w;
  std::vector<Seg> routes;
  std::vector<Point2> starts;
  Keepout keepout;
  for (const RobotPlan& r : team.robots) {
    for (const Seg& s : route_segments(r)) routes.push_back(s);
    starts.push_back(r.start);
    keepout.stops.push_back(r.start);
    for (const Op& op : r.ops) {
      if (op.kind == Op::Kind::go || op.kind == Op::Kind::patrol) keepout.stops.push_back(op.goal);
      if (op.kind == Op::Kind::patrol) keepout.stops.push_back(op.goal2);
    }
  }
  keepout.routes = routes;
  Room room{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const auto grow = [&room](Point2 p) {
    room.x0 = std::min(room.x0, p.x_m);
    room.y0 = std::min(room.y0, p.y_m);
    room.x1 = std::max(room.x1, p.x_m);
    room.y1 = std::max(room.y1, p.y_m);
  };
  for (const Seg& s : routes) {
    grow(s.a);
    grow(s.b);
  }
  for (const Point2& s : starts) grow(s);
  const bool corridor = layout == 1;
  // Goals and starts at least kStopClearance from the outer walls.
  room.x0 = std::floor((room.x0 - rng.uniform(kStopClearance, 3.0)) * 2) / 2;
  room.x1 = std::ceil((room.x1 + rng.uniform(kStopClearance, 3.0)) * 2) / 2;
  room.y0 = std::floor((room.y0 - (corridor ? rng.uniform(kStopClearance, 2.2) : rng.uniform(kStopClearance, 3.0))) * 2) / 2;
  room.y1 = std::ceil((room.y1 + (corridor ? rng.uniform(kStopClearance, 2.2) : rng.uniform(kStopClearance, 3.0))) * 2) / 2;

  // Outer walls, each with the alcoves cut into it: (side, centre, width, depth).
  struct Alcove {
    int side;
    double centre, width, depth;
  };
  std::vector<Alcove> alcoves;
  if (rng.chance(0.45)) {
    const int count = 1 + static_cast<int>(rng.integer(0, 1));
    for (int a = 0; a < count; ++a) {
      // Beside the route point nearest to a random side.
      const int side = static_cast<int>(rng.integer(0, 3));
      Point2 best{};
      double best_d = std::numeric_limits<double>::infinity();
      for (const Seg& s : routes) {
        for (const Point2& p : {s.a, s.b}) {
          const double d = side == 0 ? p.y_m - room.y0 : side == 1 ? room.x1 - p.x_m : side == 2 ? room.y1 - p.y_m : p.x_m - room.x0;
          if (d < best_d) best_d = d, best = p;
        }
      }
      const double width = round_to(rng.uniform(1.0, 2.5), 0.1);
      const double lo = (side % 2 == 0 ? room.x0 : room.y0) + width / 2 + 0.5;
      const double hi = (side % 2 == 0 ? room.x1 : room.y1) - width / 2 - 0.5;
      if (lo >= hi) continue;
      const double centre = round_to(std::clamp(side % 2 == 0 ? best.x_m : best.y_m, lo, hi), 0.1);
      bool overlaps = false;
      for (const Alcove& o : alcoves) overlaps = overlaps || (o.side == side && std::abs(o.centre - centre) < (o.width + width) / 2 + 0.5);
      if (overlaps) continue;
      alcoves.push_back({side, centre, width, round_to(rng.uniform(0.6, 1.5), 0.1)});
    }
  }
  const Point2 corner[4] = {{room.x0, room.y0}, {room.x1, room.y0}, {room.x1, room.y1}, {room.x0, room.y1}};
  for (int side = 0; side < 4; ++side) {
    const Point2 a = corner[side], b = corner[(side + 1) % 4];
    // Along the side from a to b; outward normal.
    const double ux = (b.x_m - a.x_m) / dist(a, b), uy = (b.y_m - a.y_m) / dist(a, b);
    const double nx = uy, ny = -ux;
    std::vector<Alcove> here;
    for (const Alcove& al : alcoves) {
      if (al.side == side) here.push_back(al);
    }
    // Position along the side of an alcove's centre (sides 2 and 3 run backwards).
    const auto along = [&](const Alcove& al) {
      return side == 0 ? al.centre - room.x0 : side == 1 ? al.centre - room.y0 : side == 2 ? room.x1 - al.centre : room.y1 - al.centre;
    };
    std::sort(here.begin(), here.end(), [&](const Alcove& p, const Alcove& q) { return along(p) < along(q); });
    double from = 0.0;
    const auto at = [&](double s, double out) { return Point2{a.x_m + s * ux + out * nx, a.y_m + s * uy + out * ny}; };
    for (const Alcove& al : here) {
      const double s0 = along(al) - al.width / 2, s1 = along(al) + al.width / 2;
      w.walls.push_back({at(from, 0), at(s0, 0)});
      w.walls.push_back({at(s0, 0), at(s0, al.depth)});
      w.walls.push_back({at(s0, al.depth), at(s1, al.depth)});
      w.walls.push_back({at(s1, al.depth), at(s1, 0)});
      from = s1;
      ++w.features.alcoves;
    }
    w.walls.push_back({at(from, 0), b});
  }

  // Inner walls with doorways where routes cross them: one dividing wall
  // (two rooms), or cross walls along a hallway.
  const double keep_door = 0.9;
  const auto add_divider = [&](bool vertical, double at) {
    const Point2 a = vertical ? Point2{at, room.y0} : Point2{room.x0, at};
    const Point2 b = vertical ? Point2{at, room.y1} : Point2{room.x1, at};
    std::size_t gaps = 0;
    std::vector<Seg> pieces = wall_with_doorways(a, b, keep_door, keepout, gaps);
    if (pieces.empty()) return;
    for (const Seg& p : pieces) w.walls.push_back(p);
    w.features.doorways += gaps;
  };
  if (layout == 2) {
    // Where a person would put the dividing wall: of a few places across the
    // middle, the one that leaves the most wall standing (routes cross it
    // through doorways instead of running along it).
    const bool vertical = (room.x1 - room.x0) >= (room.y1 - room.y0);
    const double lo = vertical ? room.x0 : room.y0, hi = vertical ? room.x1 : room.y1;
    double best_at = 0.0, best_solid = -1.0;
    for (int c = 0; c < 6; ++c) {
      const double at = round_to(lo + (hi - lo) * rng.uniform(0.3, 0.7), 0.5);
      const Point2 a = vertical ? Point2{at, room.y0} : Point2{room.x0, at};
      const Point2 b = vertical ? Point2{at, room.y1} : Point2{room.x1, at};
      std::size_t gaps = 0;
      double solid = 0.0;
      for (const Seg& piece : wall_with_doorways(a, b, keep_door, keepout, gaps)) solid += dist(piece.a, piece.b);
      if (solid > best_solid) best_solid = solid, best_at = at;
    }
    add_divider(vertical, best_at);
  } else if (corridor && rng.chance(0.6)) {
    const int count = 1 + static_cast<int>(rng.integer(0, 1));
    for (int c = 0; c < count; ++c) add_divider(true, round_to(rng.uniform(room.x0 + 2, room.x1 - 2), 0.5));
  }

  // Free-standing walls beside a route, and pillars.
  const auto clear_of_walls = [&w](const Seg& s, double gap) {
    for (const Seg& o : w.walls) {
      if (segment_distance(s, o) < gap) return false;
    }
    return true;
  };
  const std::size_t stubs = layout == 0 ? rng.weighted({0.3, 0.3, 0.25, 0.15}) : rng.weighted({0.5, 0.3, 0.2});
  for (std::size_t i = 0, tries = 0; i < stubs && tries < 40; ++tries) {
    const Seg& s = routes[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(routes.size()) - 1))];
    const double len = dist(s.a, s.b);
    if (len < 1.0) continue;
    // Along the nearer axis, as walls are built; the clearance check below keeps it off every route.
    const double dx = (s.b.x_m - s.a.x_m) / len, dy = (s.b.y_m - s.a.y_m) / len;
    const double ux = std::abs(dx) >= std::abs(dy) ? 1.0 : 0.0, uy = 1.0 - ux;
    const double off = rng.uniform(0.7, 1.6) * (rng.chance(0.5) ? 1 : -1);
    const double t = rng.uniform(0.0, len), half = rng.uniform(0.75, 2.5);
    const Point2 c{s.a.x_m + t * dx - off * uy, s.a.y_m + t * dy + off * ux};
    const Seg stub{{round_to(c.x_m - half * ux, 0.05), round_to(c.y_m - half * uy, 0.05)},
                   {round_to(c.x_m + half * ux, 0.05), round_to(c.y_m + half * uy, 0.05)}};
    if (!inside(room, stub.a, 0.4) || !inside(room, stub.b, 0.4)) continue;
    if (!seg_clear(stub, keepout, 0.65) || !clear_of_walls(stub, 0.6)) continue;
    w.walls.push_back(stub);
    ++w.features.wall_stubs;
    ++i;
  }
  const std::size_t pillars = layout == 0 ? rng.weighted({0.2, 0.25, 0.25, 0.15, 0.15}) : rng.weighted({0.45, 0.3, 0.25});
  for (std::size_t i = 0, tries = 0; i < pillars && tries < 60; ++tries) {
    const Seg& s = routes[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(routes.size()) - 1))];
    const double len = dist(s.a, s.b);
    if (len < 1.0) continue;
    const double ux = (s.b.x_m - s.a.x_m) / len, uy = (s.b.y_m - s.a.y_m) / len;
    const double side = round_to(rng.uniform(0.3, 0.7), 0.05);
    const double off = (rng.uniform(0.7, 1.5) + side / 2) * (rng.chance(0.5) ? 1 : -1);
    const double t = rng.uniform(0.2 * len, 0.8 * len);
    const Point2 c{round_to(s.a.x_m + t * ux - off * uy, 0.05), round_to(s.a.y_m + t * uy + off * ux, 0.05)};
    const double h = side / 2;
    const Point2 p[4] = {{c.x_m - h, c.y_m - h}, {c.x_m + h, c.y_m - h}, {c.x_m + h, c.y_m + h}, {c.x_m - h, c.y_m + h}};
    bool ok = inside(room, c, 0.8);
    for (int e = 0; e < 4 && ok; ++e) {
      const Seg edge{p[e], p[(e + 1) % 4]};
      ok = seg_clear(edge, keepout, 0.65) && clear_of_walls(edge, 0.6);
    }
    if (!ok) continue;
    for (int e = 0; e < 4; ++e) w.walls.push_back({p[e], p[(e + 1) % 4]});
    ++w.features.pillars;
    ++i;
  }

  // The robots' errors: the simulator's truth, which calibration must find.
  w.default_odometry.random_trans_per_unit = round_to(rng.log_uniform(0.003, 0.03), 0.0005);
  w.default_odometry.random_rot_per_unit = round_to(rng.log_uniform(0.003, 0.04), 0.0005);
  for (std::size_t i = 0; i < team.robots.size(); ++i) {
    sim::OdometryErrors e = w.default_odometry;
    if (rng.chance(0.6)) {
      e.left_scale = round_to(1.0 + rng.uniform(-0.04, 0.04), 0.001);
      e.right_scale = rng.chance(0.5) ? e.left_scale : round_to(1.0 + rng.uniform(-0.04, 0.04), 0.001);
    }
    if (rng.chance(0.5)) e.track_ratio = round_to(rng.uniform(0.95, 1.05), 0.005);
    if (rng.chance(0.3)) {
      e.random_trans_per_unit = round_to(rng.log_uniform(0.003, 0.03), 0.0005);
      e.random_rot_per_unit = round_to(rng.log_uniform(0.003, 0.04), 0.0005);
    }
    w.odometry.push_back(e);
  }
  w.radio.latency_min_ms = round_to(rng.uniform(0.5, 2.0), 0.1);
  w.radio.latency_median_ms = round_to(rng.uniform(2.0, 20.0), 0.5);
  w.radio.latency_sigma = round_to(rng.uniform(0.3, 0.8), 0.05);
  if (rng.chance(0.6)) {
    w.radio.slow_probability = round_to(rng.uniform(0.01, 0.2), 0.01);
    w.radio.slow_median_ms = round_to(rng.uniform(50, 400), 10);
    w.radio.slow_sigma = round_to(rng.uniform(0.3, 0.9), 0.05);
  }
  if (rng.chance(0.6)) w.radio.loss_probability = round_to(rng.uniform(0.01, 0.25), 0.01);
  return w;
}

void shift_to_origin(TeamPlan& team, WorldPlan& world) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  for (const Seg& s : world.walls) {
    x0 = std::min({x0, s.a.x_m, s.b.x_m});
    y0 = std::min({y0, s.a.y_m, s.b.y_m});
  }
  const auto move = [x0, y0](Point2& p) {
    p.x_m = round_to(p.x_m - x0, 0.05);
    p.y_m = round_to(p.y_m - y0, 0.05);
  };
  for (Seg& s : world.walls) {
    move(s.a);
    move(s.b);
  }
  for (RobotPlan& r : team.robots) {
    move(r.start);
    for (Op& op : r.ops) {
      move(op.goal);
      move(op.goal2);
    }
  }
}

}  // namespace p3at::mission_gen
