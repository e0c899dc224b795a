#pragma once
/// A CAN bus as the accessory code sees it: send and receive portable frames
/// without blocking, kernel receive timestamps, acceptance filters, and the
/// bus's error state (error frames, bus-off, interface down) with recovery.
/// Implemented by the SocketCAN backend (`socketcan://can0`) and by
/// sim::SimCanNetwork's in-process endpoints (fast time).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "p3at/common/result.hpp"
#include "p3at/protocols/can/frame.hpp"

namespace p3at::hal {

/// The controller's error state (ISO 11898 fault confinement), plus `down`
/// when the interface itself is unavailable (not up, or removed).
enum class CanBusState {
  error_active,   ///< normal operation
  error_warning,  ///< an error counter passed 96
  error_passive,  ///< an error counter passed 127: still on the bus, but degraded
  bus_off,        ///< the controller left the bus: nothing is sent or received
  down,           ///< the interface is down or gone
};

constexpr const char* to_string(CanBusState s) {
  switch (s) {
    case CanBusState::error_active: return "error-active";
    case CanBusState::error_warning: return "error-warning";
    case CanBusState::error_passive: return "error-passive";
    case CanBusState::bus_off: return "bus-off";
    case CanBusState::down: return "down";
  }
  return "?";
}

/// True when frames can be exchanged (active, warning or passive).
constexpr bool can_communicate(CanBusState s) { return s != CanBusState::bus_off && s != CanBusState::down; }

/// Acceptance filter: a frame passes when (frame.id & mask) == (id & mask) and
/// its format (standard / extended) equals `extended`. Remote frames pass too.
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool extended = false;
};

/// A received frame and when it arrived.
struct CanRxFrame {
  can::Frame frame;
  /// Arrival time on the steady (monotonic) clock, µs, the epoch of hal::SteadyClock:
  /// the kernel's receive timestamp where the backend has one, else the time of the read.
  std::int64_t stamp_us = 0;
};

/// Counters and state, cumulative since opening.
struct CanBusStatus {
  CanBusState state = CanBusState::error_active;
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_received = 0;   ///< data frames delivered by receive()
  std::uint64_t error_frames = 0;      ///< error frames reported by the controller
  std::uint64_t bus_off_events = 0;    ///< entries into bus_off
  std::uint64_t down_events = 0;       ///< entries into down
  std::uint64_t recoveries = 0;        ///< returns to a communicating state after bus_off or down
  std::uint64_t send_failures = 0;     ///< send() calls that failed (bus off/down, queue full)
  std::uint64_t rx_dropped = 0;        ///< frames the kernel dropped because we read too slowly
  std::uint64_t controller_overflows = 0;
  std::uint8_t tx_error_counter = 0;   ///< the controller's TEC/REC, when it reported them
  std::uint8_t rx_error_counter = 0;
  std::string last_error;              ///< latest error or state change, for logs; empty if none
};

/// Owned, non-copyable. Not thread-safe: one owner calls it. No call blocks
/// except wait().
class CanBus {
 public:
  CanBus() = default;
  CanBus(const CanBus&) = delete;
  CanBus& operator=(const CanBus&) = delete;
  virtual ~CanBus() = default;

  /// Queues one frame without blocking. Fails (Error::Code::state) while the
  /// bus is off or down, and (Error::Code::io) when the transmit queue is full;
  /// the frame is then dropped and counted in send_failures.
  virtual Status send(const can::Frame& frame) = 0;

  /// The next received data frame, or nullopt when none is waiting. Never blocks.
  /// Error frames and link changes are consumed here and show in status().
  /// An Error only for failures that are not a bus state (e.g. a closed bus).
  virtual Result<std::optional<CanRxFrame>> receive() = 0;

  /// Waits up to `timeout_ms` (0 = poll) for something to receive. True when
  /// receive() may return a frame or a status change; false on timeout.
  virtual Result<bool> wait(int timeout_ms) = 0;

  /// Replaces the acceptance filters. An empty list means "accept every frame"
  /// (the default after opening).
  virtual Status set_filters(std::span<const CanFilter> filters) = 0;

  /// Current state and counters.
  virtual const CanBusStatus& status() const = 0;

  /// The URL it was opened from, for messages and logs.
  virtual std::string describe() const = 0;
};

/// Opens a CAN bus from a URL:
///   `socketcan://can0`   a SocketCAN raw socket on interface can0 (Linux; `?loopback=0`
///                        stops other sockets on this host from seeing our frames)
/// A malformed URL, an unknown scheme, a missing interface or a kernel without
/// AF_CAN is an Error naming the URL, never a crash or an exception.
/// Defined, with socketcan_available(), by p3at_hal_backends (hal/backends).
Result<std::unique_ptr<CanBus>> open_can_bus(std::string_view url);

/// Whether this kernel offers AF_CAN raw sockets: ok, or an Error saying why not
/// (e.g. "socket(AF_CAN): Address family not supported by protocol").
Status socketcan_available();

}  // namespace p3at::hal
