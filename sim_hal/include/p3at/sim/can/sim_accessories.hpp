#pragma once
/// Both simulated accessories on one bus endpoint: reads the bus for NMT
/// commands, hands them to the nodes, and steps the nodes. Used in process
/// (with a SimCanNetwork endpoint) and by p3at_can_sim (with a real interface).

#include <cstdint>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/sim/can/sim_gyro.hpp"
#include "p3at/sim/can/sim_safety_node.hpp"

namespace p3at::sim {

class SimAccessories {
 public:
  /// `bus` must outlive this object. Either node may be left out.
  SimAccessories(hal::CanBus& bus, SimGyroConfig gyro, SimSafetyNodeConfig safety, bool with_gyro = true,
                 bool with_safety = true);

  /// Delivers received NMT frames to the nodes, then lets them send what fell
  /// due by `now_us`; the gyro measures `true_yaw_rate_radps`. Send failures
  /// (e.g. bus-off) are returned after both nodes were stepped.
  Status step(std::int64_t now_us, double true_yaw_rate_radps);

  SimGyro& gyro() { return gyro_; }
  SimSafetyNode& safety() { return safety_; }
  bool has_gyro() const { return with_gyro_; }
  bool has_safety() const { return with_safety_; }
  std::uint64_t frames_received() const { return frames_received_; }

 private:
  hal::CanBus& bus_;
  SimGyro gyro_;
  SimSafetyNode safety_;
  bool with_gyro_;
  bool with_safety_;
  std::uint64_t frames_received_ = 0;
};

}  // namespace p3at::sim
