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
  Publisher(hal::TeamLink& link, std::int64_t every_us) : link_(link), every_us_(every_us) {}

  /// Publishes `verdict` when due (or at once with `now`); returns the next due time.
  std::int64_t tick(std::int64_t now_us, const hal::GateVerdict& verdict, bool now = false) {
    if (now || now_us >= next_us_) {
      if (const Status st = link_.publish_verdict(verdict); !st) {
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
  hal::TeamLink& link_;
  std::int64_t every_us_;
  // Due at once: the first tick always publishes. (A plain integer rather
  // than std::optional: GCC 12 -O2 reports a false maybe-uninitialized on it.)
  std::int64_t next_us_ = std::numeric_limits<std::int64_t>::min();
  std::uint64_t published_ = 0;
  std::uint64_t errors_ = 0;
};

bool is_refusal(AgreementState state) {
  return state == AgreementState::no_go || state == AgreementState::mismatch || state == AgreementState::silent;
}

/// What the link's counters say about a silent teammate: the likely cause.
std::string diagnosis(const hal::TeamLinkStats& stats) {
  std::string out;
  if (stats.rejected_bad_tag > 0) {
    out += "; " + std::to_string(stats.rejected_bad_tag) +
           " team messages failed authentication (rejected_bad_tag): wrong team key?";
  }
  if (stats.rejected_other_mission > 0) {
    out += "; " + std::to_string(stats.rejected_other_mission) +
           " messages of another mission id (rejected_other_mission): a teammate with another mission file?";
  }
  if (stats.rejected_unknown_sender > 0) {
    out += "; " + std::to_string(stats.rejected_unknown_sender) + " messages from robots outside the roster";
  }
  return out;
}

}  // namespace

SessionResult run_gate_session(hal::TeamLink& link, hal::Clock& clock, const hal::GateVerdict& own,
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
  TeamAgreement agreement(own, roster, start_us, options.timeout_us, options.doubt_us);
  Publisher publisher(link, options.republish_us);
  std::uint64_t poll_errors = 0;
  std::set<std::string> heard;
  const auto poll = [&](std::int64_t now_us) {
    if (const Status st = link.poll(now_us, result.early); !st && poll_errors++ % 50 == 0) {
      log::warn(kLog, "event=team-poll-error error=\"" + st.error().message + "\"");
    }
    // One line per teammate the first time its verdict is heard in this gate.
    for (const hal::GateVerdict& v : link.teammate_verdicts()) {
      if (agreement.is_current(v) && heard.insert(v.robot).second) {
        log::info(kLog, "event=verdict-heard " + verdict_fields(v));
      }
    }
  };

  log::info(kLog, "event=gate-open " + verdict_fields(own) + " nonce=" + own.nonce + " team=" +
                      std::to_string(roster.size()) +
                      " timeout_s=" + fixed(static_cast<double>(options.timeout_us) / 1e6, 1));
  for (;;) {
    const std::int64_t now_us = clock.now_us();
    poll(now_us);
    const bool was_committed = agreement.current().committed;
    const Agreement& a = agreement.update(clock.now_us(), link.teammate_verdicts());
    if (a.committed && !was_committed) {
      // From now on the link speaks and listens only in this session.
      link.set_session(a.session);
      log::info(kLog, "event=gate-commit robot=" + own.robot + " session=" + a.session);
    }
    if (a.state == AgreementState::in_doubt) break;
    // Publish at once on any change (commitment, refusal), else when due.
    const bool changed = (a.committed && !was_committed) || a.state != AgreementState::waiting;
    const std::int64_t next_publish_us = publisher.tick(clock.now_us(), agreement.published(), changed);
    if (a.state != AgreementState::waiting) break;
    if (stop != nullptr && stop->load()) {
      result.interrupted = true;
      // Uncommitted, a refusal is always safe (nobody can launch without this
      // robot's commitment), and tells the team at once. Committed, a teammate
      // may have launched already: say nothing that could make others refuse.
      if (!a.committed) {
        hal::GateVerdict refusal = agreement.published();
        refusal.decision = hal::GateDecision::no_go;
        refusal.detail = "refused: interrupted by signal at the gate";
        publisher.tick(clock.now_us(), refusal, true);
      }
      break;
    }
    wait_until(std::min(next_publish_us, clock.now_us() + options.step_us));
  }
  result.waited_us = clock.now_us() - start_us;
  if (agreement.current().state == AgreementState::silent) {
    // Name the likely cause when the link's counters show one.
    Agreement explained = agreement.current();
    explained.reason += diagnosis(link.stats());
    result.agreement = explained;
  } else {
    result.agreement = agreement.current();
  }
  result.published = agreement.published();

  // After a refusal, keep telling the team why: for refusal_linger_us at
  // least, and on until every teammate has heard this gate (its verdict
  // echoes our nonce), or the gate's timeout has passed. A robot that
  // launches needs no linger: the mission's link keeps republishing.
  if (!result.interrupted && is_refusal(result.agreement.state)) {
    const std::int64_t decided_us = clock.now_us();
    const std::int64_t min_end_us = decided_us + options.refusal_linger_us;
    const std::int64_t max_end_us = std::max(min_end_us, start_us + options.timeout_us);
    const auto all_heard = [&] {
      return std::all_of(roster.begin(), roster.end(), [&](const std::string& name) {
        if (name == own.robot) return true;
        const auto& vs = link.teammate_verdicts();
        return std::any_of(vs.begin(), vs.end(),
                           [&](const hal::GateVerdict& v) { return v.robot == name && agreement.is_current(v); });
      });
    };
    for (std::int64_t now_us = clock.now_us(); now_us < max_end_us; now_us = clock.now_us()) {
      poll(now_us);
      agreement.observe(link.teammate_verdicts());
      const std::int64_t next_publish_us = publisher.tick(now_us, agreement.published());
      if (now_us >= min_end_us && all_heard()) break;
      if (stop != nullptr && stop->load()) break;
      wait_until(std::min({next_publish_us, now_us + options.step_us, max_end_us}));
    }
    result.published = agreement.published();
  }
  result.verdicts_published = publisher.published();
  return result;
}

}  // namespace p3at::gate
