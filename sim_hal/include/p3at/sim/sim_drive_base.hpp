#pragma once
/// An in-process hal::DriveBase over one simulated robot, for fast-time runs:
/// no bytes, no sockets, the executive talks to the robot's controller directly.
///
/// Time: wait_for_update() advances the World's SimClock instead of waiting.
/// Several SimDriveBases may share one World (one per robot), all driven from
/// one thread: the first that asks for a cycle its robot has not yet seen steps
/// the whole World once; the others then find that cycle ready and return at
/// once. So each World::step() serves every robot, and a round-robin loop
/// "for each robot: wait_for_update(); decide; set_velocity()" runs all robots
/// in lock-step, deterministically. Not thread-safe (neither is the World).

#include <cstddef>
#include <cstdint>

#include "p3at/hal/drive_base.hpp"
#include "p3at/protocols/arcos/sip.hpp"
#include "p3at/sim/world.hpp"

namespace p3at::sim {

class SimDriveBase final : public hal::DriveBase {
 public:
  /// Drives `world.robot(robot_index)`; `world` must outlive this object.
  /// Like a bridge after its handshake (ENABLE 1), the motors are enabled here.
  SimDriveBase(World& world, std::size_t robot_index);

  /// Velocity mode on the robot's controller (clamped to its limits). Refused
  /// (Error::Code::state) after emergency_stop() until rearm().
  Status set_velocity(double trans_mps, double rot_radps) override;
  Status stop() override;
  Status emergency_stop() override;

  /// Returns true at once if the World completed a cycle this robot has not
  /// reported yet; otherwise steps the World by one cycle (advancing its clock)
  /// and returns true, unless `timeout_ms` ends before the next cycle would: then
  /// the clock advances by `timeout_ms` and the result is false.
  Result<bool> wait_for_update(int timeout_ms) override;

  const hal::DriveState& state() const override { return state_; }

  /// Clears an emergency stop: motors on again, motion allowed.
  void rearm();

 private:
  void refresh();

  World& world_;
  std::size_t robot_index_;
  arcos::RobotParams params_;  ///< the robot's subclass's conversion factors (odometry quantisation)
  std::uint64_t seen_cycle_ = 0;
  hal::DriveState state_;
};

}  // namespace p3at::sim
