#pragma once
/// Meaning of a SocketCAN error frame (linux/can/error.h): which controller
/// state it reports and a readable description. Private to the backend.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "p3at/hal/can_bus.hpp"

namespace p3at::hal::socketcan {

struct ErrorFrameReport {
  std::optional<CanBusState> state;  ///< the state the controller reports, if any
  bool overflow = false;             ///< a controller RX/TX buffer overflowed
  bool has_counters = false;         ///< tx/rx error counters are valid
  std::uint8_t tx_error_counter = 0;
  std::uint8_t rx_error_counter = 0;
  std::string description;           ///< e.g. "bus-off", "controller: rx-passive; no-ack"
};

/// `can_id` as read from the socket (CAN_ERR_FLAG and class bits), `data` its 8 bytes.
ErrorFrameReport decode_error_frame(std::uint32_t can_id, const std::array<std::uint8_t, 8>& data);

}  // namespace p3at::hal::socketcan
