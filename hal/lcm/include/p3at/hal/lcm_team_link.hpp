#pragma once
/// The team link over LCM (UDP multicast between robots). The only code that
/// includes lcm-cpp.hpp is its implementation, hal/lcm/lcm_team_link.cpp.
/// Channels, types and rules: docs/team-link.md.

#include <memory>
#include <string_view>

#include "p3at/common/result.hpp"
#include "p3at/team_link/team_key.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/gate_verdict.hpp"
#include "p3at/team_link/team_protocol.hpp"

namespace p3at::hal {

/// LCM's own default: multicast group 239.255.76.67, port 7667, packets never
/// leave the host (ttl=0). Robots on a real network use ttl=1.
inline constexpr std::string_view kDefaultTeamLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// Opens this robot's end of the team link on `lcm_url`:
///   `udpm://GROUP:PORT?ttl=N`  UDP multicast (robots, hardware-in-the-loop tests)
///   `memq://`                  in-process queue (one instance hears only itself)
/// Overrides config.first_seq with the wall-clock time in microseconds since
/// the epoch (so a restarted robot's sequence numbers are newer than any it
/// used before, as long as its clock does not step back), and
/// config.utime_offset_us so that messages' utime is wall-clock time when
/// poll() is given hal::SteadyClock time.
/// Errors name the URL: invalid config, unsupported scheme, or LCM unable to
/// open it (e.g. no route for multicast). Never throws.
/// The link subscribes to and publishes on P3AT_NOTIFY, P3AT_STATUS,
/// P3AT_GATE and P3AT_TELEMETRY.
Result<std::unique_ptr<gate::VerdictLink>> open_lcm_team_link(std::string_view lcm_url, TeamLinkConfig config,
                                                     const TeamKey& key);

}  // namespace p3at::hal
