#pragma once
/// A listening TCP socket, for servers such as the firmware emulator p3at_sim.

#include <memory>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/byte_stream.hpp"

namespace p3at::hal {

class TcpListener {
 public:
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;
  ~TcpListener();

  /// Listens on host:port (SO_REUSEADDR). Port 0 picks a free port (see port()),
  /// host "" listens on all interfaces. A busy port (refused), an address this
  /// machine lacks (not_found) or a port outside 0-65535 (invalid_argument) is
  /// an Error naming them.
  static Result<std::unique_ptr<TcpListener>> listen(const std::string& host, int port);

  /// Accepts one pending connection, waiting at most `timeout_ms` (0 = poll).
  /// Returns nullptr on timeout. The accepted stream has TCP_NODELAY set.
  Result<std::unique_ptr<ByteStream>> accept(int timeout_ms);

  /// The bound port (useful after listening on port 0).
  int port() const { return port_; }

 private:
  TcpListener(int fd, int port) : fd_(fd), port_(port) {}
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace p3at::hal
