#pragma once
// Test double: two in-memory hal::ByteStreams joined back to back. Bytes
// written to one end are read from the other; closing one end makes the other
// end's reads fail with Error::Code::closed once it has drained what was sent.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "p3at/hal/byte_stream.hpp"

namespace p3at::sim::test {

struct MemoryPipe {
  std::deque<std::uint8_t> to_b;  // written by end a
  std::deque<std::uint8_t> to_a;  // written by end b
  bool a_closed = false;
  bool b_closed = false;
};

class MemoryStream final : public hal::ByteStream {
 public:
  MemoryStream(std::shared_ptr<MemoryPipe> pipe, bool is_a) : pipe_(std::move(pipe)), is_a_(is_a) {}

  Status write_all(std::span<const std::uint8_t> bytes) override {
    if (self_closed() || peer_closed()) return make_error(Error::Code::closed, describe() + ": closed");
    auto& out = is_a_ ? pipe_->to_b : pipe_->to_a;
    out.insert(out.end(), bytes.begin(), bytes.end());
    return {};
  }

  Result<std::size_t> read_some(std::span<std::uint8_t> buffer, int /*timeout_ms*/) override {
    if (self_closed()) return make_error(Error::Code::closed, describe() + ": closed");
    auto& in = is_a_ ? pipe_->to_a : pipe_->to_b;
    if (in.empty()) {
      if (peer_closed()) return make_error(Error::Code::closed, describe() + ": peer closed");
      return std::size_t{0};
    }
    const std::size_t n = std::min(buffer.size(), in.size());
    std::copy_n(in.begin(), n, buffer.begin());
    in.erase(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }

  void close() override { (is_a_ ? pipe_->a_closed : pipe_->b_closed) = true; }

  std::string describe() const override { return is_a_ ? "memory://a" : "memory://b"; }

  bool peer_closed() const { return is_a_ ? pipe_->b_closed : pipe_->a_closed; }

 private:
  bool self_closed() const { return is_a_ ? pipe_->a_closed : pipe_->b_closed; }

  std::shared_ptr<MemoryPipe> pipe_;
  bool is_a_;
};

/// (client end, robot end).
inline std::pair<std::unique_ptr<MemoryStream>, std::unique_ptr<MemoryStream>> make_stream_pair() {
  auto pipe = std::make_shared<MemoryPipe>();
  return {std::make_unique<MemoryStream>(pipe, true), std::make_unique<MemoryStream>(pipe, false)};
}

}  // namespace p3at::sim::test
