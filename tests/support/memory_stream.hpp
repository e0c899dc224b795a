#pragma once
// An in-process pair of connected byte streams, for unit tests of code that
// talks over a hal::ByteStream (the bridge, the firmware emulator). Shared by
// every test folder: fakes live in one place.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "p3at/hal/byte_stream.hpp"

namespace p3at::test {

/// Shared state of one direction of a pipe.
struct PipeBuffer {
  std::deque<std::uint8_t> bytes;
  bool closed = false;
};

/// One end of a MemoryPipe. read_some never sleeps; when nothing is buffered it
/// calls `on_idle(timeout_ms)` (if set) once, which a test uses to advance a
/// fake clock or to let the peer run, then reads again.
class MemoryStream final : public hal::ByteStream {
 public:
  MemoryStream(std::shared_ptr<PipeBuffer> in, std::shared_ptr<PipeBuffer> out, std::string name)
      : in_(std::move(in)), out_(std::move(out)), name_(std::move(name)) {}

  Status write_all(std::span<const std::uint8_t> bytes) override {
    if (closed_ || out_->closed) return make_error(Error::Code::closed, name_ + ": closed");
    out_->bytes.insert(out_->bytes.end(), bytes.begin(), bytes.end());
    written_ += bytes.size();
    if (on_write) on_write();
    return {};
  }

  Result<std::size_t> read_some(std::span<std::uint8_t> buffer, int timeout_ms) override {
    if (closed_) return make_error(Error::Code::closed, name_ + ": closed");
    if (in_->bytes.empty() && on_idle) on_idle(timeout_ms);
    if (in_->bytes.empty()) {
      if (in_->closed) return make_error(Error::Code::closed, name_ + ": peer closed");
      return std::size_t{0};
    }
    const std::size_t n = std::min(buffer.size(), std::min(in_->bytes.size(), max_read_chunk));
    std::copy_n(in_->bytes.begin(), n, buffer.begin());
    in_->bytes.erase(in_->bytes.begin(), in_->bytes.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }

  void close() override {
    closed_ = true;
    out_->closed = true;
    in_->closed = true;
  }

  std::string describe() const override { return name_; }

  /// Called when a read finds nothing buffered; gets the read's timeout.
  std::function<void(int timeout_ms)> on_idle;
  /// Called after every write (a test uses it to let the peer react at once).
  std::function<void()> on_write;
  /// Largest number of bytes one read_some returns (to exercise split packets).
  std::size_t max_read_chunk = 4096;
  std::size_t written() const { return written_; }
  /// True once the other end has closed (and this one has not).
  bool peer_closed() const { return in_->closed && !closed_; }

 private:
  std::shared_ptr<PipeBuffer> in_;
  std::shared_ptr<PipeBuffer> out_;
  std::string name_;
  bool closed_ = false;
  std::size_t written_ = 0;
};

/// Two connected ends: what `a` writes, `b` reads, and back.
struct MemoryPipe {
  std::shared_ptr<PipeBuffer> a_to_b = std::make_shared<PipeBuffer>();
  std::shared_ptr<PipeBuffer> b_to_a = std::make_shared<PipeBuffer>();
  std::unique_ptr<MemoryStream> make_a() { return std::make_unique<MemoryStream>(b_to_a, a_to_b, "memory://a"); }
  std::unique_ptr<MemoryStream> make_b() { return std::make_unique<MemoryStream>(a_to_b, b_to_a, "memory://b"); }
};

}  // namespace p3at::test
