#pragma once
/// Teammates' liveness during the mission (docs/executive.md, "Liveness"):
/// every authenticated message of the session is a heartbeat (telemetry goes
/// out every cycle). A teammate that has not finished or aborted and has been
/// silent for longer than the limit is reported once; mission_exec then takes
/// the mission's abort_action. Pure but for the link it reads: time comes in.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "p3at/hal/team_link.hpp"

namespace p3at::gate {

struct SilentTeammate {
  std::string robot;
  double silent_s = 0;  ///< since its last message (or since launch, if none since)
};

class TeammateWatch {
 public:
  /// `teammates`: the roster without this robot. `limit_us` > 0.
  TeammateWatch(std::vector<std::string> teammates, std::int64_t limit_us);

  /// Starts the clocks: a teammate not heard since counts as heard at `now_us`.
  void start(std::int64_t now_us);
  /// Teammates newly silent past the limit at `now_us` (link time, the time
  /// the link was polled with). Each is reported once, and again only after
  /// it has been heard from in between.
  std::vector<SilentTeammate> check(std::int64_t now_us, const hal::TeamLink& link);
  std::int64_t limit_us() const { return limit_us_; }

 private:
  std::vector<std::string> teammates_;
  std::int64_t limit_us_;
  std::int64_t start_us_ = 0;
  bool started_ = false;
  std::map<std::string, std::int64_t> reported_at_;  ///< last-heard time when reported
};

}  // namespace p3at::gate
