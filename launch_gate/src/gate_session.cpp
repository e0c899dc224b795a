#include "p3at/launch_gate/gate_session.hpp"

#include <algorithm>
#include <limits>
#include <set>

#include "p3at/common/log.hpp"
#include "p3at/launch_gate/check_report.hpp"

namespace p3at::gate {
namespace {

constexpr const char* kLog = "gate";

class Publisher {
 public:
  Publisher(VerdictLink& link, const gate::GateVerdict& own, std::int64_t every_us)
      : link_(link), own_(own), every_us_(every_us) {}

  /// Publishes when due; returns the next due time.
  std::int64_t tick(std::int64_t now_us) {
    if (now_us >= next_us_) {
      if (const Status st = link_.publish_verdict(own_); !st) {
        if (errors_++ % 50 == 0) log::warn(kLog, "event=publish-error what=verdict error=\"" + st.error().message + "\"");
      } else {
        ++published_;
      }
      next_us_ = now_us + every_us_;
    }
    return next_us_;
  }
  std::uint64_t published() const { return published_; }

 private:
  VerdictLink& link_;
  const gate::GateVerdict& own_;
  std::int64_t every_us_;
  // Due at once: the first tick always publishes. (A plain integer rather
  // than std::optional: GCC 12 -O2 reports a false maybe-uninitialized on it.)
  std::int64_t next_us_ = std::numeric_limits<std::int64_t>::min();
  std::uint64_t published_ = 0;
  std::uint64_t errors_ = 0;
};

}  // namespace

SessionResult run_gate_session(VerdictLink& link, hal::Clock& clock, const gate::GateVerdict& own,
                               const std::vector<std::string>& roster, const SessionOptions& options,
                               const std::function<void(std::int64_t)>& pace, const std::atomic<bool>* stop) {
  const auto wait_until = [&](std::int64_t deadline_us) {
    if (pace) {
      pace(deadline_us);
    } else {
      clock.sleep_until_us(deadline_us);
    }
  };
  SessionResult result;
  const std::int64_t start_us = clock.now_us();
  TeamAgreement agreement(own, roster, start_us, options.timeout_us);
  Publisher publisher(link, own, options.republish_us);
  std::uint64_t poll_errors = 0;
  std::set<std::string> heard;
  const auto poll = [&](std::int64_t now_us) {
    if (const Status st = link.poll(now_us, result.early); !st && poll_errors++ % 50 == 0) {
      log::warn(kLog, "event=team-poll-error error=\"" + st.error().message + "\"");
    }
    // One line per teammate the first time its verdict is heard.
    for (const gate::GateVerdict& v : link.teammate_verdicts()) {
      if (heard.insert(v.robot).second) log::info(kLog, "event=verdict-heard " + verdict_fields(v));
    }
  };

  log::info(kLog, "event=gate-open " + verdict_fields(own) + " team=" + std::to_string(roster.size()) +
                      " timeout_s=" + fixed(static_cast<double>(options.timeout_us) / 1e6, 1));
  for (;;) {
    const std::int64_t now_us = clock.now_us();
    const std::int64_t next_publish_us = publisher.tick(now_us);
    poll(now_us);
    if (agreement.update(clock.now_us(), link.teammate_verdicts()).state != AgreementState::waiting) break;
    if (stop != nullptr && stop->load()) {
      result.interrupted = true;
      break;
    }
    wait_until(std::min(next_publish_us, clock.now_us() + options.step_us));
  }
  result.waited_us = clock.now_us() - start_us;
  result.agreement = agreement.current();

  // After a refusal, keep telling the team why: for refusal_linger_us at
  // least, and on until every teammate has been heard from (a robot that has
  // published is listening, so it will hear this one) or the gate's timeout
  // has passed. A robot that launches needs no linger: the mission's link
  // keeps republishing.
  if (!result.interrupted && result.agreement.state != AgreementState::launch) {
    const std::int64_t decided_us = clock.now_us();
    const std::int64_t min_end_us = decided_us + options.refusal_linger_us;
    const std::int64_t max_end_us = std::max(min_end_us, start_us + options.timeout_us);
    const auto all_heard = [&] {
      return std::all_of(roster.begin(), roster.end(),
                         [&](const std::string& name) { return name == own.robot || heard.count(name) != 0; });
    };
    for (std::int64_t now_us = clock.now_us(); now_us < max_end_us; now_us = clock.now_us()) {
      const std::int64_t next_publish_us = publisher.tick(now_us);
      poll(now_us);
      if (now_us >= min_end_us && all_heard()) break;
      if (stop != nullptr && stop->load()) break;
      wait_until(std::min({next_publish_us, now_us + options.step_us, max_end_us}));
    }
  }
  result.verdicts_published = publisher.published();
  return result;
}

}  // namespace p3at::gate
