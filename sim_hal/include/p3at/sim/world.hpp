#pragma once
/// The simulated world: walls, the robots in it, and the one clock they share.
///
/// Ownership and threading: a World owns its robots and its SimClock. Nothing
/// in it is thread-safe; one thread steps it. Everything that acts on a robot
/// (a FirmwareEmulator, a SimDriveBase) holds a reference to the World and a
/// robot index, and must not outlive the World. step() advances every robot by
/// one 100 ms controller cycle at once, so a multi-robot run steps the world once
/// per cycle for all robots (SimDriveBase::wait_for_update relies on this: the
/// first robot to ask for a new cycle steps the world, the others find the
/// cycle already done).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "p3at/sim/geometry.hpp"
#include "p3at/sim/sim_clock.hpp"
#include "p3at/sim/sim_robot.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::sim {

class World {
 public:
  /// Physics steps per 100 ms cycle (10 ms each): collisions are found within
  /// one step's travel (6 mm at 0.6 m/s).
  static constexpr int kSubstepsPerCycle = 10;

  /// Builds the world; robot i draws its random numbers from (seed, i).
  explicit World(const WorldConfig& config, std::uint64_t seed = 1);
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  std::size_t robot_count() const { return robots_.size(); }
  SimRobot& robot(std::size_t index) { return robots_.at(index); }
  const SimRobot& robot(std::size_t index) const { return robots_.at(index); }
  /// Index of the robot with this name, if any.
  std::optional<std::size_t> find_robot(std::string_view name) const;
  std::span<const Segment> walls() const { return walls_; }

  /// The clock every component of this world reads. step() advances it; a
  /// caller may also sleep on it, and then advance_to() lets the world catch up.
  SimClock& clock() { return clock_; }
  const SimClock& clock() const { return clock_; }

  /// Simulated time of the last completed cycle, microseconds (a multiple of kCycleUs).
  std::int64_t time_us() const { return time_us_; }
  /// Completed cycles since the start.
  std::uint64_t cycle_count() const { return cycles_; }

  /// One controller cycle (kCycleUs) for every robot: physics substeps in robot
  /// index order, then the sonar of every robot. The clock moves to time_us().
  void step();

  /// Steps whole cycles while a full cycle still ends at or before `time_us`.
  void advance_to(std::int64_t time_us);

 private:
  std::vector<Segment> walls_;
  std::vector<SimRobot> robots_;
  SimClock clock_;
  std::int64_t time_us_ = 0;
  std::uint64_t cycles_ = 0;
  /// others_ = the boxes of every robot but `index`, where they are now.
  void collect_others(std::size_t index);

  // Scratch space reused every step (no allocation per cycle).
  std::vector<Box> others_;
};

}  // namespace p3at::sim
