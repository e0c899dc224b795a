#pragma once
/// An in-process CAN bus for fast-time runs: endpoints are hal::CanBus objects;
/// a frame one endpoint sends reaches every other endpoint at once, stamped
/// with the shared clock. No threads, no sockets, no waiting.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/clock.hpp"

namespace p3at::sim {

class SimCanNetwork {
 public:
  /// `clock` stamps deliveries and must outlive the network and its endpoints.
  explicit SimCanNetwork(const hal::Clock& clock, std::size_t rx_queue_limit = 4096);
  ~SimCanNetwork();
  SimCanNetwork(const SimCanNetwork&) = delete;
  SimCanNetwork& operator=(const SimCanNetwork&) = delete;

  /// A new endpoint named `name` (its describe() is "sim-can://NAME"). It may
  /// outlive the network object; it then stays connected to its other endpoints.
  std::unique_ptr<hal::CanBus> attach(const std::string& name);

  /// Puts every endpoint's controller in `state`, as a controller's error frames
  /// or the interface going down would: bus_off and down stop all traffic; a
  /// communicating state restores it. `why` is reported in each status().last_error.
  void set_state(hal::CanBusState state, const std::string& why);

  hal::CanBusState state() const;
  /// Frames delivered to endpoints (one frame to two endpoints counts twice).
  std::uint64_t deliveries() const;

  struct Core;  // shared with the endpoints

 private:
  std::shared_ptr<Core> core_;
};

}  // namespace p3at::sim
