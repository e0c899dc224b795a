#pragma once
/// The safety node's watchdog and the re-arm latch (docs/can-bus.md, "Safety latch").

#include <cstdint>
#include <optional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/protocols/can/accessories.hpp"
#include "p3at/protocols/can/canopen.hpp"

namespace p3at::bridge {

struct SafetyMonitorConfig {
  std::int64_t heartbeat_period_us = can::kHeartbeatPeriodUs;  ///< the node's heartbeat producer time
  int missed_heartbeats = 3;                                    ///< trip after this many periods of silence
  std::int64_t state_period_us = can::kSafetyPdoPeriodUs;       ///< the node's TPDO1 period
  int missed_states = 3;                                        ///< trip after this many periods without a state
};

/// What the drive base must do this cycle.
struct SafetyVerdict {
  bool stop_now = false;        ///< a new trip: emergency-stop now (ESTOP, motors off). True once per trip.
  bool motion_allowed = false;  ///< armed, and nothing asks to stop
  bool clear = false;           ///< the node reports clear right now: rearm() would succeed
  std::string why;              ///< when motion is not allowed: the trip's cause, and what still blocks re-arming
};

/// The evidence at the latest trip, for logs and latency checks.
struct SafetyTrip {
  std::int64_t at_us = 0;               ///< evaluate() time that tripped
  std::int64_t state_stamp_us = 0;      ///< arrival of the latest state message then (0 if none)
  std::int64_t heartbeat_stamp_us = 0;  ///< arrival of the latest heartbeat then (0 if none)
  std::string why;
};

/// Trips (latches) on: e-stop pressed, a bumper hit, the node's fault flag or an
/// active EMCY, its heartbeat missing for `missed_heartbeats` periods, its NMT
/// state not operational, its state message stale, or the bus off or down.
/// Once tripped, motion stays refused until the node reports clear AND rearm()
/// is called. Starts disarmed. Times are steady µs. Not thread-safe.
class SafetyMonitor {
 public:
  explicit SafetyMonitor(std::uint8_t node_id, SafetyMonitorConfig config = {});

  void on_state(const can::SafetyState& state, std::int64_t stamp_us);
  void on_heartbeat(can::NmtState state, std::int64_t stamp_us);
  /// An EMCY with a non-zero code makes the node not clear until an EMCY with code 0 (error reset).
  void on_emergency(const can::Emergency& emergency);
  void on_bus_state(hal::CanBusState state, const std::string& detail);

  /// Checks everything at `now_us` and latches a trip when armed and not clear.
  SafetyVerdict evaluate(std::int64_t now_us);

  /// Arms: succeeds only when nothing blocks at `now_us`; otherwise an
  /// Error::Code::state saying what blocks.
  Status rearm(std::int64_t now_us);

  /// Why the node is not clear at `now_us`, or nullopt when it is.
  std::optional<std::string> blocking_reason(std::int64_t now_us) const;

  bool armed() const { return armed_; }
  /// Stamp (steady µs) of the latest accepted state message, 0 before the first.
  std::int64_t state_stamp_us() const { return state_ ? state_us_ : 0; }
  /// Stamp of the latest heartbeat, 0 before the first.
  std::int64_t heartbeat_stamp_us() const { return nmt_ ? heartbeat_us_ : 0; }
  /// The latest trip (all zero before the first).
  const SafetyTrip& last_trip() const { return last_trip_; }
  std::uint64_t trips() const { return trips_; }
  std::uint8_t node_id() const { return node_id_; }

 private:
  std::uint8_t node_id_;
  SafetyMonitorConfig config_;
  bool armed_ = false;
  std::string trip_why_ = "not armed yet";
  std::uint64_t trips_ = 0;
  SafetyTrip last_trip_;
  std::optional<can::SafetyState> state_;
  std::int64_t state_us_ = 0;
  std::optional<can::NmtState> nmt_;
  std::int64_t heartbeat_us_ = 0;
  std::optional<can::Emergency> emergency_;
  hal::CanBusState bus_ = hal::CanBusState::error_active;
  std::string bus_detail_;
};

}  // namespace p3at::bridge
