#pragma once
/// Anti-replay bookkeeping for one sender's sequence numbers: the sliding
/// window of IPsec ESP (RFC 4303, section 3.4.3). A sequence number is fresh if
/// it is above every one accepted so far, or within the window below the highest
/// and not accepted yet (the radio may reorder); anything else is a replay.
/// Pure and tiny: one per (receiver, sender).

#include <bitset>
#include <cstdint>

namespace p3at::hal {

class ReplayWindow {
 public:
  /// How far below the highest accepted sequence number a late one is still taken.
  static constexpr std::uint64_t kSize = 256;

  enum class Verdict {
    fresh,      ///< never accepted: deliver it
    duplicate,  ///< accepted before (a retransmission or a replay within the window)
    too_old,    ///< kSize or more below the highest accepted: cannot tell, so refused
  };

  /// What accept(seq) would mean, without changing anything.
  Verdict check(std::uint64_t seq) const;

  /// Records `seq` as accepted. Returns check(seq) as it was before the call;
  /// only `fresh` changes the window.
  Verdict accept(std::uint64_t seq);

  /// The highest sequence number accepted so far (0 before the first).
  std::uint64_t highest() const { return highest_; }

 private:
  bool any_ = false;
  std::uint64_t highest_ = 0;
  std::bitset<kSize> seen_;  ///< bit i: highest_ - i has been accepted
};

}  // namespace p3at::hal
