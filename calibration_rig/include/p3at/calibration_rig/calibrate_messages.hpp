#pragma once
// Notifications across the simulated team link (sim::SimRadio, the world
// file's `radio:` block) in fast time, timed as a lab would time them on the
// robots: sent (the Notify), delivered (the recipient's process has the
// datagram), acknowledged (the sender's process has the ack).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "p3at/sim/radio.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::vipars {

struct MessagePlan {
  std::size_t count = 400;
  /// The robots' control period: each robot's executive polls the link once
  /// per cycle, so an acknowledgement leaves the recipient at its next cycle.
  double cycle_s = 0.1;
  /// false: every robot's cycle starts at the same instants (as in fast-time
  /// team runs); true: each recipient's cycle has its own phase, drawn per
  /// message (robots with unsynchronised clocks).
  bool random_phase = false;
};

/// `count` notifications, round robin over the ordered pairs of `robots` (with
/// one robot, to a stand-in teammate). Throws std::runtime_error when the
/// radio or the link cannot be set up.
std::vector<verifier::MessageRow> measure_messages(const sim::RadioParams& radio, const std::vector<std::string>& robots,
                                                   const MessagePlan& plan, std::uint64_t seed);

}  // namespace p3at::vipars
