#pragma once
// Private to p3at_hal's TCP backend: small POSIX helpers shared by the stream
// and the listener.

#include <cerrno>
#include <string>

#include "p3at/common/result.hpp"

namespace p3at::hal::tcp_detail {

/// Waits until `fd` reports one of `events` (POLLIN, POLLOUT) or `timeout_ms`
/// passes (0 = poll once; negative is treated as 0). Restarts after EINTR with
/// the remaining time. Returns the revents seen, 0 on timeout.
/// `what` prefixes the message of an Error::Code::io error.
Result<short> wait_fd(int fd, short events, int timeout_ms, const std::string& what);

/// The operating system's text for an errno value, e.g. "Connection refused".
std::string errno_text(int err);

/// True for "try again later" from a non-blocking socket call.
inline bool would_block(int err) {
#if EAGAIN == EWOULDBLOCK
  return err == EAGAIN;
#else
  return err == EAGAIN || err == EWOULDBLOCK;
#endif
}

/// Sets TCP_NODELAY and O_NONBLOCK on a connected socket.
Status prepare_connected_socket(int fd, const std::string& what);

}  // namespace p3at::hal::tcp_detail
