#pragma once
// Private to p3at_hal: the SocketCAN backend of hal::CanBus. The only code in
// the project that includes linux/can.h (in the .cpp files).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "p3at/hal/can_bus.hpp"

namespace p3at::hal::socketcan {

struct SocketCanOptions {
  std::string url;              ///< for messages
  std::string interface_name;   ///< e.g. "can0", "vcan0"
  bool loopback = true;         ///< other sockets on this host see our frames (CAN_RAW_LOOPBACK)
  bool receive_own = false;     ///< we see our own frames (CAN_RAW_RECV_OWN_MSGS)
};

/// Opens and binds a raw CAN socket with error frames, receive timestamps and
/// drop counting enabled.
Result<std::unique_ptr<CanBus>> open_socketcan(const SocketCanOptions& options);

}  // namespace p3at::hal::socketcan
