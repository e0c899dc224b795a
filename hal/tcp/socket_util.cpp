#include "tcp/socket_util.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <system_error>

namespace p3at::hal::tcp_detail {

Result<short> wait_fd(int fd, short events, int timeout_ms, const std::string& what) {
  using std::chrono::steady_clock;
  const int budget_ms = std::max(timeout_ms, 0);
  const auto deadline = steady_clock::now() + std::chrono::milliseconds(budget_ms);
  int remaining_ms = budget_ms;
  for (;;) {
    pollfd pfd{};
    pfd.fd = fd;
    pfd.events = events;
    const int n = ::poll(&pfd, 1, remaining_ms);
    if (n > 0) return pfd.revents;
    if (n == 0) return static_cast<short>(0);
    const int err = errno;
    if (err != EINTR) return make_error(Error::Code::io, what + ": poll failed: " + errno_text(err));
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - steady_clock::now());
    remaining_ms = static_cast<int>(std::max<std::chrono::milliseconds::rep>(left.count(), 0));
  }
}

std::string errno_text(int err) { return std::system_category().message(err); }

Status prepare_connected_socket(int fd, const std::string& what) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
    const int err = errno;
    return make_error(Error::Code::io, what + ": cannot make the socket non-blocking: " + errno_text(err));
  }
  // ARCOS packets are small and latency-sensitive: never let Nagle hold them back.
  const int one = 1;
  if (::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one) < 0) {
    const int err = errno;
    return make_error(Error::Code::io, what + ": cannot set TCP_NODELAY: " + errno_text(err));
  }
  return {};
}

}  // namespace p3at::hal::tcp_detail
