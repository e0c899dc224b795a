#pragma once
// What the generator draws before it becomes text: routes, walls, each
// robot's script of operations. Shared by the generator's source files only.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "gen_rng.hpp"
#include "p3at/mission_gen/generator.hpp"
#include "p3at/protocols/mission/mission.hpp"
#include "p3at/sim/robot_model.hpp"
#include "p3at/sim/radio.hpp"

namespace p3at::mission_gen {

using mission::Point2;

struct Seg {
  Point2 a, b;
};

inline double dist(Point2 p, Point2 q) { return std::hypot(p.x_m - q.x_m, p.y_m - q.y_m); }
/// Distance from p to the segment s.
double point_segment_distance(Point2 p, const Seg& s);
/// Smallest distance between two segments (0 when they cross).
double segment_distance(const Seg& s, const Seg& t);
/// True when the two segments cross at a point inside both.
bool segments_cross(const Seg& s, const Seg& t);

/// One step of a robot's script; becomes one state (two for a patrol).
struct Op {
  enum class Kind { go, spin, notify, wait, patrol };
  Kind kind = Kind::go;
  Point2 goal;                      ///< go; patrol's first corner
  Point2 goal2;                     ///< patrol's second corner
  mission::GoToGuardedParams go_params;   ///< go and both patrol states (goal set when written)
  double radius_m = 0.3;            ///< AtGoal radius
  double rate_deg_s = 30.0;         ///< spin
  double angle_deg = 90.0, offset_deg = 0.0;  ///< spin's HasTurned
  std::string message;              ///< notify: sent; wait, patrol: awaited
  std::string recall;               ///< go, spin: a Notified leaving the state mid-way ("" none)
  bool recall_first = false;        ///< the Notified is checked before the AtGoal / HasTurned
  int recall_target = -1;           ///< op index the recall jumps to; ops.size() = the final Stop
  bool exit_first = false;          ///< patrol: Notified listed before AtGoal
};

struct RobotPlan {
  std::string name;
  Point2 start;
  double theta_deg = 0.0;
  double max_speed_mps = 0.3;
  std::vector<Op> ops;
};

struct MessagePlan {
  std::string name;
  std::size_t from = 0;
  std::vector<std::size_t> to;
};

struct TeamPlan {
  std::vector<RobotPlan> robots;
  std::vector<MessagePlan> messages;
  std::vector<std::size_t> order;   ///< a robot waits only for robots earlier in this order
  bool corridor = false;            ///< a hallway: routes run along x
};

struct WorldPlan {
  std::vector<Seg> walls;
  WorldFeatures features;
  std::vector<sim::OdometryErrors> odometry;   ///< per robot
  sim::OdometryErrors default_odometry;
  sim::RadioParams radio;
};

/// The route segments a robot's centre may follow (legs, patrol laps, the
/// shortcuts a recall takes), for clearance checks and crossings.
std::vector<Seg> route_segments(const RobotPlan& robot);

/// Draws the robots' starts, routes and scripts (without messages).
TeamPlan draw_routes(GenRng& rng, std::size_t robots, bool corridor);
/// Adds the team's messages: waits, recalls, patrol exits, multi-recipient sends.
void draw_messages(GenRng& rng, TeamPlan& team);
/// Walls around and among the routes, and the robots' and radio's errors.
WorldPlan draw_world(GenRng& rng, const TeamPlan& team, int layout);
/// Shifts everything so the room's lower-left corner is near (0, 0).
void shift_to_origin(TeamPlan& team, WorldPlan& world);

/// A rough nominal completion time of the team, s (for the criteria).
double nominal_time_s(const TeamPlan& team);

std::string mission_text(const TeamPlan& team, const mission::Criteria& criteria, const std::string& name,
                         const std::string& description, std::uint64_t seed);
std::string world_text(const TeamPlan& team, const WorldPlan& world, std::uint64_t seed);

/// Shortest decimal that reads back as `x` after rounding to 1e-9 (people write 0.35).
std::string num(double x);

}  // namespace p3at::mission_gen
