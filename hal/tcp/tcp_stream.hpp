#pragma once
// Private to p3at_hal: a ByteStream over a connected TCP socket. Users reach it
// through open_byte_stream("tcp://HOST:PORT") or TcpListener::accept.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "p3at/common/result.hpp"
#include "p3at/hal/byte_stream.hpp"

namespace p3at::hal {

/// Owns one connected, non-blocking TCP socket with TCP_NODELAY set.
class TcpStream final : public ByteStream {
 public:
  /// How long write_all waits for the peer to make room in the send buffer
  /// before giving up with Error::Code::timeout (ms without any progress).
  static constexpr int kWriteStallTimeoutMs = 2000;

  /// Connects to host:port (names resolved with getaddrinfo, every address
  /// tried in turn) within `timeout_ms` in total. `url` is used in messages.
  /// Errors: refused (nothing listening), not_found (unknown host),
  /// timeout, io. Name resolution itself is not bounded by the timeout.
  static Result<std::unique_ptr<TcpStream>> connect(const std::string& url, const std::string& host, int port,
                                                    int timeout_ms);

  /// Adopts an already connected socket `fd` (ownership passes to the stream);
  /// makes it non-blocking and sets TCP_NODELAY. `description` names the peer.
  static Result<std::unique_ptr<TcpStream>> adopt(int fd, std::string description);

  ~TcpStream() override;

  Status write_all(std::span<const std::uint8_t> bytes) override;
  Result<std::size_t> read_some(std::span<std::uint8_t> buffer, int timeout_ms) override;
  void close() override;
  std::string describe() const override { return description_; }

 private:
  TcpStream(int fd, std::string description) : fd_(fd), description_(std::move(description)) {}
  Error closed_error() const;

  int fd_ = -1;
  std::string description_;
};

}  // namespace p3at::hal
