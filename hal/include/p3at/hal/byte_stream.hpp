#pragma once
/// A bidirectional byte stream to a robot controller: a serial port or a TCP
/// connection carry identical ARCOS bytes.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "p3at/common/result.hpp"

namespace p3at::hal {

/// Owned, non-copyable connection. Not thread-safe: one owner calls it.
class ByteStream {
 public:
  ByteStream() = default;
  ByteStream(const ByteStream&) = delete;
  ByteStream& operator=(const ByteStream&) = delete;
  virtual ~ByteStream() = default;

  /// Writes every byte, or fails. Blocks only while the OS cannot take more,
  /// and for a bounded time (Error::Code::timeout when the peer stops reading).
  /// Error::Code::closed when the peer has gone; never raises SIGPIPE.
  virtual Status write_all(std::span<const std::uint8_t> bytes) = 0;

  /// Reads what is available, waiting at most `timeout_ms` (0 or negative =
  /// just poll). Returns the number of bytes read; 0 means the wait timed out
  /// (or `buffer` is empty). Error::Code::closed when the peer has closed the
  /// stream or the device went away.
  virtual Result<std::size_t> read_some(std::span<std::uint8_t> buffer, int timeout_ms) = 0;

  /// Releases the connection; further calls fail with Error::Code::closed.
  virtual void close() = 0;

  /// The URL it was opened from, for messages and logs.
  virtual std::string describe() const = 0;
};

/// Opens a byte stream from a URL:
///   `tcp://HOST:PORT`                 a TCP connection (Pioneer simulators, p3at_sim)
///   `serial:///dev/ttyS0?baud=9600`   a serial port, 8N1, no flow control
/// A malformed URL, unknown scheme, missing port or refused connection is an
/// Error naming the URL, never a crash or an exception: invalid_argument (bad
/// URL, scheme, baud, timeout <= 0), not_found (unknown host, missing device),
/// refused (nothing listening, device busy or not permitted), timeout.
/// `connect_timeout_ms` bounds the TCP connect (not name resolution).
/// See docs/hal.md. Defined by p3at_hal_backends (hal/backends), the one
/// target that knows the backends: link it to open streams by URL.
Result<std::unique_ptr<ByteStream>> open_byte_stream(std::string_view url, int connect_timeout_ms = 2000);

}  // namespace p3at::hal
