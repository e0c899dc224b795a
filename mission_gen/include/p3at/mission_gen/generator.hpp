#pragma once
/// Generated missions (docs/crosscheck.md): a valid mission, its world and its
/// criteria, drawn deterministically from a seed, shaped like the missions
/// people write. The cross-check campaign (crosscheck/) runs `vipars verify`
/// against `vipars validate` on them; nothing here knows of either.
///
/// The same seed gives the same bytes on any machine: the random stream is
/// SplitMix64 with our own uniform transforms (no <random> distributions,
/// which differ between standard libraries).

#include <cstdint>
#include <string>
#include <vector>

#include "p3at/protocols/mission/mission.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::mission_gen {

/// The simulator's P3-AT top speed (sim::MotionLimits::max_trans_vel_mps):
/// no generated robot is asked to go faster.
inline constexpr double kTopSpeedMps = 0.6;

struct GenerateOptions {
  std::uint64_t seed = 1;
  std::size_t min_robots = 1;  ///< 1..6
  std::size_t max_robots = 6;  ///< min_robots..6
};

/// What the world holds besides its four outer walls, for pictures and coverage.
struct WorldFeatures {
  std::size_t pillars = 0;        ///< small square obstacles near a path
  std::size_t wall_stubs = 0;     ///< free-standing walls beside a path
  std::size_t doorways = 0;       ///< cross walls a path goes through by a gap
  std::size_t alcoves = 0;        ///< recesses in an outer wall beside a path
};

/// One robot's intended route: its start and the goals of its GoToGuarded
/// states in the order the script visits them (for pictures; the FSA is the truth).
struct RoutePlan {
  std::string robot;
  std::vector<mission::Point2> points;  ///< start first
};

struct GeneratedMission {
  std::uint64_t seed = 0;
  std::string name;                     ///< gen_<seed>
  std::string mission_yaml;             ///< the mission file's text
  std::string world_yaml;               ///< the world file's text
  mission::Mission mission;             ///< mission_yaml, loaded by the mission loader
  sim::WorldConfig world;               ///< world_yaml, loaded by the world loader
  WorldFeatures features;
  std::vector<RoutePlan> routes;
};

/// Draws one mission. Throws std::invalid_argument for a bad robot range and
/// std::logic_error if what it drew does not load (a generator bug: the
/// loaders are the judges).
GeneratedMission generate(const GenerateOptions& options);

/// What a mission exercises, counted from the loaded mission and world (not
/// from the generator's intentions), for coverage tables and tests.
struct Coverage {
  std::size_t robots = 0;
  std::size_t go_to_states = 0;
  double min_leg_m = 0.0, max_leg_m = 0.0;         ///< straight-line leg lengths between consecutive goals
  double min_speed_mps = 0.0, max_speed_mps = 0.0;
  double min_dropoff_m = 0.0, max_dropoff_m = 0.0;
  double max_noise_gain = 0.0;
  std::size_t noise_redrawn_every_cycle = 0;       ///< GoToGuarded states with persistence 1
  std::size_t noise_held_whole_leg = 0;            ///< persistence >= the leg's nominal cycles
  std::size_t spins = 0;                           ///< Spin states left by HasTurned
  std::size_t spin_offsets = 0;                    ///< HasTurned with offset_deg > 0
  std::size_t loops = 0;                           ///< robots whose FSA has a cycle
  std::size_t notified_from_moving = 0;            ///< Notified leaving a GoToGuarded
  std::size_t notified_from_spin = 0;              ///< Notified leaving a Spin
  std::size_t notified_from_stop = 0;              ///< Notified leaving a Stop
  std::size_t at_goal_racing_notified = 0;         ///< states left by both AtGoal and Notified
  std::size_t multi_recipient_messages = 0;
  std::size_t crossing_paths = 0;                  ///< pairs of robots whose routes cross
  WorldFeatures world;
  std::size_t systematic_error_robots = 0;         ///< wheel scale or track ratio off 1 by > 0.5 %
  double min_random_trans = 0.0, max_random_trans = 0.0;
  bool lossy_radio = false;
  bool slow_radio = false;
};
Coverage coverage(const GeneratedMission& generated);

/// Writes DIR/mission.yaml and DIR/world.yaml, creating DIR. Throws
/// std::runtime_error naming the file that cannot be written.
void write_generated(const GeneratedMission& generated, const std::string& dir);

/// How many of `missions` exercise each feature, one line per feature (the
/// coverage table of docs/crosscheck.md).
std::string coverage_table(const std::vector<Coverage>& missions);

/// A picture of the world: walls, start poses, each robot's route. Writes
/// BASE.dat, BASE.gp and (unless gnuplot is empty) runs `gnuplot BASE.gp` to
/// make BASE.png. Returns "" or gnuplot's complaint.
std::string draw_picture(const GeneratedMission& generated, const std::string& base_path,
                         const std::string& gnuplot = "gnuplot");

}  // namespace p3at::mission_gen
