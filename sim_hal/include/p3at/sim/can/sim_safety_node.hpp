#pragma once
/// A simulated safety node on the CAN bus (CANopen node, TPDO1 at 20 Hz and on
/// every change, docs/can-bus.md): an e-stop button, eight bumper segments, a
/// fault flag with EMCY, and silence to simulate a lost node.

#include <cstdint>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/protocols/can/accessories.hpp"
#include "p3at/sim/can/sim_canopen_node.hpp"

namespace p3at::sim {

struct SimSafetyNodeConfig {
  std::uint8_t node_id = can::kDefaultSafetyNodeId;
  std::int64_t period_us = can::kSafetyPdoPeriodUs;
  std::int64_t heartbeat_period_us = can::kHeartbeatPeriodUs;
  bool auto_start = false;  ///< operational without waiting for NMT start
};

class SimSafetyNode {
 public:
  explicit SimSafetyNode(SimSafetyNodeConfig config);

  void on_frame(const can::Frame& frame) { node_.on_frame(frame); }

  /// Sends what fell due up to `now_us`: boot-up and heartbeats, a pending EMCY,
  /// and (when operational) the state every period and at once after a change.
  Status step(hal::CanBus& bus, std::int64_t now_us);

  void press_estop(bool pressed);
  /// Bits 0-3 front segments, 4-7 rear; 1 = pressed.
  void set_bumpers(std::uint8_t bumpers);
  /// The node's fault flag plus an EMCY with `code` (clearing sends EMCY 0x0000).
  void set_fault(bool fault, std::uint16_t code = can::emcy_code::kEstopCircuit);
  void set_silent(bool silent) { node_.set_silent(silent); }
  void reboot() { node_.reboot(); }

  /// The state as the next message will carry it (counter excluded).
  can::SafetyState state() const { return state_; }
  const SimCanopenNode& node() const { return node_; }
  std::uint64_t states_sent() const { return states_sent_; }

 private:
  SimSafetyNodeConfig config_;
  SimCanopenNode node_;
  can::SafetyState state_;
  std::uint64_t generation_seen_ = 0;
  std::int64_t next_state_us_ = 0;
  bool changed_ = false;
  bool emcy_pending_ = false;
  std::uint16_t emcy_code_ = 0;
  std::uint64_t states_sent_ = 0;
};

}  // namespace p3at::sim
