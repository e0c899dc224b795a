#pragma once
/// The CAN accessories seen from the bridge: reads the bus, decodes the gyro
/// and the safety node (docs/can-bus.md), keeps their NMT state, and offers
/// the two things the drive base needs each cycle: a safety verdict and a
/// gyro-aided pose. Bad input is counted and ignored, never fatal.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/drive_base.hpp"
#include "p3at/bridge/accessories/gyro_integrator.hpp"
#include "p3at/bridge/accessories/heading_fuser.hpp"
#include "p3at/bridge/accessories/safety_monitor.hpp"
#include "p3at/bridge/accessories/sequence_tracker.hpp"
#include "p3at/protocols/can/accessories.hpp"

namespace p3at::bridge {

struct AccessoryConfig {
  std::uint8_t gyro_node_id = can::kDefaultGyroNodeId;
  std::uint8_t safety_node_id = can::kDefaultSafetyNodeId;
  std::int64_t gyro_period_us = can::kGyroPdoPeriodUs;
  int gyro_missed_samples = 5;        ///< the gyro is not used after this many periods without a sample
  bool start_nodes = true;            ///< send NMT start to a node that boots or reports pre-operational
  std::size_t max_frames_per_poll = 1000;  ///< bounds one poll's work
  GyroIntegratorConfig gyro;
  HeadingFuserConfig fusion;
  SafetyMonitorConfig safety;
};

/// Every frame read is counted once in `frames` and at most once in one of the
/// rejection counters. Counters are never reset.
struct AccessoryCounters {
  std::uint64_t frames = 0;          ///< data frames read from the bus
  std::uint64_t unknown_id = 0;      ///< COB-IDs of no configured node (or extended / remote frames)
  std::uint64_t wrong_length = 0;    ///< a known message with the wrong length
  std::uint64_t stale_counter = 0;   ///< a TPDO whose counter repeats or goes back
  std::uint64_t bad_payload = 0;     ///< right length, undecodable (check byte, unknown state or flags)
  std::uint64_t ignored = 0;         ///< valid CANopen traffic we do not use (NMT, SYNC, other PDOs)
  std::uint64_t gyro_samples = 0;
  std::uint64_t gyro_lost_samples = 0;  ///< counter gaps
  std::uint64_t safety_states = 0;
  std::uint64_t heartbeats = 0;
  std::uint64_t emergencies = 0;
  std::uint64_t nmt_sent = 0;
  std::uint64_t send_failures = 0;
  std::uint64_t receive_errors = 0;
};

/// Not thread-safe: one loop calls it. Holds a reference to the bus, which must outlive it.
class AccessoryHub {
 public:
  explicit AccessoryHub(hal::CanBus& bus, AccessoryConfig config = {});

  /// Broadcasts NMT "start" so both nodes go operational. Safe to repeat.
  Status start();

  /// Reads every waiting frame (never blocks), updates the devices, and returns
  /// what the drive base must do now. Call at least once per control cycle.
  SafetyVerdict poll(std::int64_t now_us);

  /// Standstill from the drive base, for the gyro's bias estimation.
  void set_standstill(bool still, std::int64_t now_us) { gyro_.set_standstill(still, now_us); }
  /// The same, derived from a drive state (standing still: not moving, wheels at rest).
  void observe(const hal::DriveState& state) { set_standstill(is_standstill(state), state.stamp_us); }

  /// The gyro-aided pose for an odometry pose taken at `stamp_us`.
  hal::Pose2 aided_pose(const hal::Pose2& odometry, std::int64_t stamp_us);
  /// Only the heading of aided_pose(); use one or the other in a loop, not both.
  double fused_heading(const hal::Pose2& odometry, std::int64_t stamp_us) {
    return aided_pose(odometry, stamp_us).theta_rad;
  }

  /// Re-arms the safety latch (see SafetyMonitor::rearm).
  Status rearm(std::int64_t now_us) { return safety_.rearm(now_us); }

  /// Gyro samples fresh, no fault flag or EMCY, node operational, bias learned.
  bool gyro_usable(std::int64_t now_us) const;
  /// Why the gyro is not usable, or empty.
  std::string gyro_problem(std::int64_t now_us) const;

  const AccessoryCounters& counters() const { return counters_; }
  const GyroIntegrator& gyro() const { return gyro_; }
  const HeadingFuser& fuser() const { return fuser_; }
  const SafetyMonitor& safety() const { return safety_; }
  const hal::CanBus& bus() const { return bus_; }
  const AccessoryConfig& config() const { return config_; }

  static bool is_standstill(const hal::DriveState& state);

 private:
  void handle(const hal::CanRxFrame& rx, std::int64_t now_us);
  void handle_gyro_pdo(const hal::CanRxFrame& rx);
  void handle_safety_pdo(const hal::CanRxFrame& rx);
  void handle_heartbeat(std::uint8_t node_id, const hal::CanRxFrame& rx, std::int64_t now_us);
  void handle_emcy(std::uint8_t node_id, const hal::CanRxFrame& rx);
  void send_nmt_start(std::uint8_t node_id, std::int64_t now_us);

  hal::CanBus& bus_;
  AccessoryConfig config_;
  GyroIntegrator gyro_;
  HeadingFuser fuser_;
  SafetyMonitor safety_;
  AccessoryCounters counters_;
  SequenceTracker gyro_seq_;
  SequenceTracker safety_seq_;
  bool gyro_fault_flag_ = false;
  std::optional<can::Emergency> gyro_emergency_;
  std::optional<can::NmtState> gyro_nmt_;
  std::int64_t last_gyro_frame_us_ = 0;
  std::int64_t last_safety_frame_us_ = 0;
  std::array<std::int64_t, 2> last_nmt_sent_us_{INT64_MIN / 2, INT64_MIN / 2};  // gyro, safety
};

}  // namespace p3at::bridge
