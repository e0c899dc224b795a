#include "p3at/launch_gate/teammate_watch.hpp"

#include <algorithm>
#include <utility>

namespace p3at::gate {

TeammateWatch::TeammateWatch(std::vector<std::string> teammates, std::int64_t limit_us)
    : teammates_(std::move(teammates)), limit_us_(std::max<std::int64_t>(1, limit_us)) {}

void TeammateWatch::start(std::int64_t now_us) {
  start_us_ = now_us;
  started_ = true;
}

std::vector<SilentTeammate> TeammateWatch::check(std::int64_t now_us, const hal::TeamLink& link) {
  std::vector<SilentTeammate> silent;
  if (!started_) return silent;
  const auto& statuses = link.teammate_status();
  for (const std::string& name : teammates_) {
    // A teammate that has finished or aborted may stop talking: that is not silence.
    const auto st = std::find_if(statuses.begin(), statuses.end(),
                                 [&](const hal::TeamStatus& s) { return s.robot == name; });
    if (st != statuses.end() && (st->phase == "finished" || st->phase == "aborted")) continue;
    const std::int64_t heard_us = std::max(start_us_, link.last_heard_us(name).value_or(start_us_));
    const auto reported = reported_at_.find(name);
    if (reported != reported_at_.end() && reported->second == heard_us) continue;  // said already
    if (now_us - heard_us > limit_us_) {
      reported_at_[name] = heard_us;
      silent.push_back({name, static_cast<double>(now_us - heard_us) / 1e6});
    }
  }
  return silent;
}

}  // namespace p3at::gate
