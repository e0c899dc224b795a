#pragma once
/// Stale-counter detection for the 8-bit counters in our TPDOs.

#include <cstdint>

namespace p3at::bridge {

/// Follows one node's wrapping 8-bit message counter.
class SequenceTracker {
 public:
  /// Steps since the last accepted counter: 1 normally, n > 1 after n - 1 lost
  /// messages, 0 when the counter is stale (repeated, or behind: more than 127
  /// steps ahead means behind). The first counter after construction or
  /// reset() is accepted as 1 step. A stale counter leaves the state unchanged.
  std::uint32_t accept(std::uint8_t counter) {
    if (!has_last_) {
      has_last_ = true;
      last_ = counter;
      return 1;
    }
    const auto delta = static_cast<std::uint8_t>(counter - last_);
    if (delta == 0 || delta > 127) return 0;
    last_ = counter;
    return delta;
  }

  /// Forget the last counter (after the node restarted or fell silent for long).
  void reset() { has_last_ = false; }

  bool has_last() const { return has_last_; }

 private:
  bool has_last_ = false;
  std::uint8_t last_ = 0;
};

}  // namespace p3at::bridge
