#include "p3at/hal/tcp_listener.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

#include "tcp/socket_util.hpp"
#include "tcp/tcp_stream.hpp"

namespace p3at::hal {
namespace {

using tcp_detail::errno_text;

constexpr int kBacklog = 8;
constexpr int kMaxPort = 65535;

struct AddrInfoDeleter {
  void operator()(addrinfo* list) const { ::freeaddrinfo(list); }
};

std::string endpoint_text(const std::string& host, const std::string& port) {
  const bool ipv6 = host.find(':') != std::string::npos;
  return (ipv6 ? "[" + host + "]" : host) + ":" + port;
}

// "tcp://HOST:PORT" of a socket address, for describing accepted peers.
std::string describe_peer(const sockaddr_storage& addr, socklen_t len) {
  char host[NI_MAXHOST] = {};
  char service[NI_MAXSERV] = {};
  const int rc = ::getnameinfo(reinterpret_cast<const sockaddr*>(&addr), len, host, sizeof host, service,
                               sizeof service, NI_NUMERICHOST | NI_NUMERICSERV);
  if (rc != 0) return "tcp://(unknown peer)";
  return "tcp://" + endpoint_text(host, service);
}

Error listen_error(const std::string& where, const char* step, int err) {
  switch (err) {
    case EADDRINUSE:
      return make_error(Error::Code::refused, "listen on " + where + ": address already in use");
    case EACCES:
    case EPERM:
      return make_error(Error::Code::refused, "listen on " + where + ": permission denied");
    case EADDRNOTAVAIL:
      return make_error(Error::Code::not_found, "listen on " + where + ": address not available on this machine");
    default:
      return make_error(Error::Code::io, "listen on " + where + ": " + step + " failed: " + errno_text(err));
  }
}

}  // namespace

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::unique_ptr<TcpListener>> TcpListener::listen(const std::string& host, int port) {
  const std::string where = endpoint_text(host.empty() ? "*" : host, std::to_string(port));
  if (port < 0 || port > kMaxPort) {
    return make_error(Error::Code::invalid_argument, "listen on " + where + ": port out of range (expected 0-65535)");
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* raw = nullptr;
  const std::string service = std::to_string(port);
  const int rc = ::getaddrinfo(host.empty() ? nullptr : host.c_str(), service.c_str(), &hints, &raw);
  if (rc != 0) {
    return make_error(Error::Code::not_found, "listen on " + where + ": unknown address (" + ::gai_strerror(rc) + ")");
  }
  const std::unique_ptr<addrinfo, AddrInfoDeleter> list(raw);

  Error last = make_error(Error::Code::not_found, "listen on " + where + ": no usable address");
  for (const addrinfo* ai = list.get(); ai != nullptr; ai = ai->ai_next) {
    const int fd = ::socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) {
      last = listen_error(where, "socket", errno);
      continue;
    }
    // Restarting p3at_sim must not wait for TIME_WAIT connections of the last run.
    const int one = 1;
    const char* step = "setsockopt(SO_REUSEADDR)";
    bool ok = ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) == 0;
    if (ok) {
      step = "bind";
      ok = ::bind(fd, ai->ai_addr, ai->ai_addrlen) == 0;
    }
    if (ok) {
      step = "listen";
      ok = ::listen(fd, kBacklog) == 0;
    }
    sockaddr_storage bound{};
    socklen_t len = sizeof bound;
    if (ok) {
      step = "getsockname";
      ok = ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &len) == 0;
    }
    if (!ok) {
      last = listen_error(where, step, errno);
      ::close(fd);
      continue;
    }
    int bound_port = port;
    if (bound.ss_family == AF_INET) {
      bound_port = ntohs(reinterpret_cast<const sockaddr_in*>(&bound)->sin_port);
    } else if (bound.ss_family == AF_INET6) {
      bound_port = ntohs(reinterpret_cast<const sockaddr_in6*>(&bound)->sin6_port);
    }
    return std::unique_ptr<TcpListener>(new TcpListener(fd, bound_port));
  }
  return last;
}

Result<std::unique_ptr<ByteStream>> TcpListener::accept(int timeout_ms) {
  const std::string where = "listener on port " + std::to_string(port_);
  if (fd_ < 0) return make_error(Error::Code::closed, where + ": not listening");
  for (;;) {
    sockaddr_storage peer{};
    socklen_t len = sizeof peer;
    const int fd = ::accept4(fd_, reinterpret_cast<sockaddr*>(&peer), &len, SOCK_CLOEXEC);
    if (fd >= 0) {
      auto stream = TcpStream::adopt(fd, describe_peer(peer, len));
      if (!stream) return stream.error();
      return std::unique_ptr<ByteStream>(std::move(stream).value());
    }
    const int err = errno;
    if (err == EINTR) continue;
    // The peer may have given up between poll() and accept(): just wait again.
    if (err == ECONNABORTED) continue;
    if (!tcp_detail::would_block(err)) {
      return make_error(Error::Code::io, where + ": accept failed: " + errno_text(err));
    }
    auto ready = tcp_detail::wait_fd(fd_, POLLIN, timeout_ms, where);
    if (!ready) return ready.error();
    if (*ready == 0) return std::unique_ptr<ByteStream>{};
    timeout_ms = 0;  // one wait per call: after it, take what is there or report a timeout
  }
}

}  // namespace p3at::hal
