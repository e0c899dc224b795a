#include "tcp/tcp_stream.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>

#include "tcp/socket_util.hpp"

namespace p3at::hal {
namespace {

using tcp_detail::errno_text;
using tcp_detail::wait_fd;

// RAII for the getaddrinfo list.
struct AddrInfoDeleter {
  void operator()(addrinfo* list) const { ::freeaddrinfo(list); }
};
using AddrInfoList = std::unique_ptr<addrinfo, AddrInfoDeleter>;

Error connect_error(const std::string& url, int err) {
  switch (err) {
    case ECONNREFUSED: return make_error(Error::Code::refused, url + ": connection refused");
    case ETIMEDOUT: return make_error(Error::Code::timeout, url + ": connection timed out");
    default: return make_error(Error::Code::io, url + ": cannot connect: " + errno_text(err));
  }
}

Result<AddrInfoList> resolve(const std::string& url, const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV;
  addrinfo* list = nullptr;
  const std::string service = std::to_string(port);
  const int rc = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &list);
  if (rc == 0) return AddrInfoList(list);
  const int err = errno;
  switch (rc) {
    case EAI_NONAME:
    case EAI_NODATA:
    case EAI_AGAIN:
    case EAI_FAMILY:
      return make_error(Error::Code::not_found,
                        url + ": unknown host '" + host + "' (" + ::gai_strerror(rc) + ")");
    case EAI_SYSTEM:
      return make_error(Error::Code::io, url + ": cannot resolve '" + host + "': " + errno_text(err));
    default:
      return make_error(Error::Code::io, url + ": cannot resolve '" + host + "': " + ::gai_strerror(rc));
  }
}

// One non-blocking connect attempt, bounded by `timeout_ms`. Returns the
// connected socket or the errno-style reason it failed (ETIMEDOUT on timeout).
struct Attempt {
  int fd = -1;
  int err = 0;
  Error poll_error{};
  bool poll_failed = false;
};

Attempt try_connect(const addrinfo& ai, int timeout_ms, const std::string& url) {
  Attempt a;
  const int fd = ::socket(ai.ai_family, ai.ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai.ai_protocol);
  if (fd < 0) {
    a.err = errno;
    return a;
  }
  if (::connect(fd, ai.ai_addr, ai.ai_addrlen) == 0) {
    a.fd = fd;
    return a;
  }
  const int err = errno;
  // A non-blocking connect interrupted by a signal carries on in the background.
  if (err != EINPROGRESS && err != EINTR) {
    ::close(fd);
    a.err = err;
    return a;
  }
  auto ready = wait_fd(fd, POLLOUT, timeout_ms, url);
  if (!ready) {
    ::close(fd);
    a.poll_failed = true;
    a.poll_error = ready.error();
    return a;
  }
  if (*ready == 0) {
    ::close(fd);
    a.err = ETIMEDOUT;
    return a;
  }
  int so_error = 0;
  socklen_t len = sizeof so_error;
  if (::getsockopt(fd, SOL_SOCKET, SO_ERROR, &so_error, &len) < 0) so_error = errno;
  if (so_error != 0) {
    ::close(fd);
    a.err = so_error;
    return a;
  }
  a.fd = fd;
  return a;
}

}  // namespace

Result<std::unique_ptr<TcpStream>> TcpStream::connect(const std::string& url, const std::string& host, int port,
                                                      int timeout_ms) {
  auto list = resolve(url, host, port);
  if (!list) return list.error();

  using std::chrono::steady_clock;
  const auto deadline = steady_clock::now() + std::chrono::milliseconds(std::max(timeout_ms, 0));
  Error last = make_error(Error::Code::not_found, url + ": host '" + host + "' has no usable address");
  for (const addrinfo* ai = list->get(); ai != nullptr; ai = ai->ai_next) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - steady_clock::now());
    const int left_ms = static_cast<int>(std::max<std::chrono::milliseconds::rep>(left.count(), 0));
    Attempt a = try_connect(*ai, left_ms, url);
    if (a.fd >= 0) return adopt(a.fd, url);
    last = a.poll_failed ? a.poll_error : connect_error(url, a.err);
    if (steady_clock::now() >= deadline) break;
  }
  if (last.code == Error::Code::timeout) {
    last.message = url + ": no connection within " + std::to_string(timeout_ms) + " ms";
  }
  return last;
}

Result<std::unique_ptr<TcpStream>> TcpStream::adopt(int fd, std::string description) {
  if (auto st = tcp_detail::prepare_connected_socket(fd, description); !st) {
    ::close(fd);
    return st.error();
  }
  return std::unique_ptr<TcpStream>(new TcpStream(fd, std::move(description)));
}

TcpStream::~TcpStream() { close(); }

Error TcpStream::closed_error() const {
  return make_error(Error::Code::closed, description_ + ": stream is closed");
}

Status TcpStream::write_all(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) return closed_error();
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n >= 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    const int err = errno;
    if (err == EINTR) continue;
    if (tcp_detail::would_block(err)) {
      auto ready = wait_fd(fd_, POLLOUT, kWriteStallTimeoutMs, description_);
      if (!ready) return ready.error();
      if (*ready == 0) {
        return make_error(Error::Code::timeout, description_ + ": peer is not reading: sent " + std::to_string(sent) +
                                                    " of " + std::to_string(bytes.size()) + " bytes, then no room for " +
                                                    std::to_string(kWriteStallTimeoutMs) + " ms");
      }
      continue;  // writable, or an error the next send() will report
    }
    if (err == EPIPE || err == ECONNRESET) {
      return make_error(Error::Code::closed, description_ + ": connection closed by peer (" + errno_text(err) + ")");
    }
    return make_error(Error::Code::io, description_ + ": send failed: " + errno_text(err));
  }
  return {};
}

Result<std::size_t> TcpStream::read_some(std::span<std::uint8_t> buffer, int timeout_ms) {
  if (fd_ < 0) return closed_error();
  if (buffer.empty()) return std::size_t{0};
  bool waited = false;
  for (;;) {
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    if (n > 0) return static_cast<std::size_t>(n);
    if (n == 0) return make_error(Error::Code::closed, description_ + ": connection closed by peer");
    const int err = errno;
    if (err == EINTR) continue;
    if (err == ECONNRESET) return make_error(Error::Code::closed, description_ + ": connection reset by peer");
    if (!tcp_detail::would_block(err)) {
      return make_error(Error::Code::io, description_ + ": recv failed: " + errno_text(err));
    }
    if (waited || timeout_ms <= 0) return std::size_t{0};
    auto ready = wait_fd(fd_, POLLIN, timeout_ms, description_);
    if (!ready) return ready.error();
    if (*ready == 0) return std::size_t{0};
    waited = true;
  }
}

void TcpStream::close() {
  if (fd_ >= 0) {
    // Linux releases the descriptor even when close() reports EINTR: never retry.
    ::close(fd_);
    fd_ = -1;
  }
}

}  // namespace p3at::hal
