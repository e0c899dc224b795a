#pragma once
/// The CANopen behaviour every simulated accessory shares (CiA 301 NMT slave):
/// boot-up message, pre-operational until NMT start, heartbeat producer,
/// reset and stop commands. Devices own one and add their PDOs.

#include <cstdint>
#include <optional>

#include "p3at/common/result.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/protocols/can/canopen.hpp"

namespace p3at::sim {

class SimCanopenNode {
 public:
  /// `auto_start`: go operational right after boot-up (a node configured to
  /// start itself), instead of waiting for NMT start.
  SimCanopenNode(std::uint8_t node_id, std::int64_t heartbeat_period_us, bool auto_start);

  /// Applies an NMT command addressed to this node or to all; other frames are ignored.
  void on_frame(const can::Frame& frame);

  /// Sends the boot-up message on the first call after (re)boot, then a heartbeat
  /// each period. Silent nodes send nothing. Returns the first send error.
  Status step(hal::CanBus& bus, std::int64_t now_us);

  /// Simulates a power cycle: the next step() sends boot-up again.
  void reboot();
  /// A silent node transmits nothing (its owner must honour silent() too).
  void set_silent(bool silent) { silent_ = silent; }
  bool silent() const { return silent_; }

  can::NmtState state() const { return state_; }
  bool operational() const { return state_ == can::NmtState::operational && !silent_ && booted_; }
  std::uint8_t node_id() const { return node_id_; }
  /// Increments on every boot-up and NMT reset: owners restart their counters.
  std::uint64_t generation() const { return generation_; }

 private:
  std::uint8_t node_id_;
  std::int64_t heartbeat_period_us_;
  bool auto_start_;
  bool booted_ = false;
  bool silent_ = false;
  can::NmtState state_ = can::NmtState::pre_operational;
  std::int64_t next_heartbeat_us_ = 0;
  std::uint64_t generation_ = 0;
};

}  // namespace p3at::sim
