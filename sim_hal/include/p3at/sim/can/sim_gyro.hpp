#pragma once
/// A simulated yaw-rate gyro on the CAN bus (CANopen node, TPDO1 at 100 Hz,
/// docs/can-bus.md): it measures a true yaw rate with a bias, white noise and
/// a scale error, and can be made faulty or silent.

#include <cstdint>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/protocols/can/accessories.hpp"
#include "p3at/sim/can/sim_canopen_node.hpp"
#include "p3at/sim/rng.hpp"

namespace p3at::sim {

struct SimGyroConfig {
  std::uint8_t node_id = can::kDefaultGyroNodeId;
  double bias_radps = 0.0;        ///< offset at boot
  double bias_drift_radps_per_s = 0.0;  ///< linear change of the offset with time since the first step
  double noise_sd_radps = 0.0;    ///< white noise per sample, 1 sigma
  double scale_error = 0.0;       ///< measured = (1 + scale_error) · true + bias + noise
  double range_radps = 8.7;       ///< ±500 °/s; beyond it the reading clips and the saturated bit is set
  double temperature_c = 35.0;
  std::int64_t period_us = can::kGyroPdoPeriodUs;
  std::int64_t heartbeat_period_us = can::kHeartbeatPeriodUs;
  bool auto_start = false;        ///< operational without waiting for NMT start
  std::uint64_t seed = 1;         ///< the noise's random stream
};

class SimGyro {
 public:
  explicit SimGyro(SimGyroConfig config);

  /// Handles NMT commands from the bus.
  void on_frame(const can::Frame& frame) { node_.on_frame(frame); }

  /// Sends what fell due up to `now_us`: boot-up and heartbeats, any pending
  /// EMCY, and (when operational) one TPDO per period measuring `true_rate_radps`:
  /// (1 + scale_error) · true + bias + drift · t + noise, clipped to ±range.
  Status step(hal::CanBus& bus, std::int64_t now_us, double true_rate_radps);

  /// A sensor fault: the status bit in every sample and an EMCY with `code`;
  /// clearing it sends EMCY 0x0000 (error reset).
  void set_fault(bool fault, std::uint16_t code = can::emcy_code::kDeviceHardware);
  void set_silent(bool silent) { node_.set_silent(silent); }
  void reboot() { node_.reboot(); }

  const SimCanopenNode& node() const { return node_; }
  std::uint64_t samples_sent() const { return samples_sent_; }
  double last_measured_radps() const { return last_measured_radps_; }
  const SimGyroConfig& config() const { return config_; }

 private:
  SimGyroConfig config_;
  SimCanopenNode node_;
  Rng rng_;
  std::uint64_t generation_seen_ = 0;
  bool started_ = false;
  std::int64_t first_step_us_ = 0;
  std::int64_t next_sample_us_ = 0;
  std::uint8_t counter_ = 0;
  bool fault_ = false;
  bool emcy_pending_ = false;
  std::uint16_t emcy_code_ = 0;
  std::uint64_t samples_sent_ = 0;
  double last_measured_radps_ = 0.0;
};

}  // namespace p3at::sim
