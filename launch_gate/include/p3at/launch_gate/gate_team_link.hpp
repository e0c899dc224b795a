#pragma once
/// The team link as mission_exec hands it to the executive: a hal::TeamLink
/// that forwards to the real one and adds what the launch gate needs during
/// the mission, without the executive knowing about the gate:
///  - the real link always runs on `link_clock` (wall time), whatever time the
///    executive passes to poll() (it passes mission time, docs/launch-gate.md),
///    so retransmissions and utime keep their meaning under a fast simulator;
///  - notifications that arrived during the gate (a teammate that launched
///    first may notify at once) are handed to the executive on its first poll();
///  - this robot's gate verdict is republished every `republish_us` during the
///    mission, so a teammate still waiting at its gate hears it;
///  - published status carries the latest re-verified probability (and a note
///    while running, e.g. a continue-and-warn);
///  - after every poll(), `after_poll` runs (the in-mission monitor's hook).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/team_link.hpp"

namespace p3at::gate {

class GateTeamLink final : public hal::TeamLink {
 public:
  /// `inner` and `link_clock` must outlive this object.
  GateTeamLink(hal::TeamLink& inner, hal::Clock& link_clock) : inner_(inner), link_clock_(link_clock) {}

  // ---- hal::TeamLink
  Result<std::uint64_t> notify(const std::string& message, const std::vector<std::string>& recipients) override {
    return inner_.notify(message, recipients);
  }
  bool acknowledged(std::uint64_t seq) const override { return inner_.acknowledged(seq); }
  /// Polls the real link at link_clock time (`now_us` is ignored), delivers
  /// held-over notifications first, republishes the verdict when due, then
  /// runs after_poll.
  Status poll(std::int64_t now_us, std::vector<hal::TeamNotification>& received) override;
  Status publish_telemetry(const hal::Telemetry& telemetry) override { return inner_.publish_telemetry(telemetry); }
  /// Forwards `status` with p_success replaced by the latest re-verified
  /// probability (if any) and, while running with no reason, the note.
  Status publish_status(const hal::TeamStatus& status) override;
  const std::vector<hal::TeamStatus>& teammate_status() const override { return inner_.teammate_status(); }
  Status publish_verdict(const hal::GateVerdict& verdict) override { return inner_.publish_verdict(verdict); }
  const std::vector<hal::GateVerdict>& teammate_verdicts() const override { return inner_.teammate_verdicts(); }
  const std::vector<hal::Telemetry>& teammate_telemetry() const override { return inner_.teammate_telemetry(); }
  const hal::TeamLinkStats& stats() const override { return inner_.stats(); }
  void set_session(const std::string& session) override { inner_.set_session(session); }
  const std::string& session() const override { return inner_.session(); }
  /// In link_clock time (the real link's), not the executive's.
  std::optional<std::int64_t> last_heard_us(const std::string& robot) const override {
    return inner_.last_heard_us(robot);
  }

  // ---- the gate's additions
  /// Notifications received while the gate was deciding: delivered first by the next poll().
  void hand_over(std::vector<hal::TeamNotification> early);
  /// Republish `verdict` every `republish_us` of link time from the next poll() on.
  void keep_publishing(hal::GateVerdict verdict, std::int64_t republish_us);
  /// The probability published in status from now on; republishes the latest status at once.
  void set_p_success(double p_success);
  /// A note for the status reason while the mission runs (empty: none).
  void set_note(std::string note) { note_ = std::move(note); }
  std::optional<double> p_success() const { return p_success_; }
  std::uint64_t verdicts_republished() const { return verdicts_republished_; }

  std::function<void()> after_poll;

 private:
  hal::TeamLink& inner_;
  hal::Clock& link_clock_;
  std::vector<hal::TeamNotification> early_;
  std::optional<hal::GateVerdict> verdict_;
  std::int64_t republish_us_ = 0;
  std::optional<std::int64_t> next_verdict_us_;
  std::uint64_t verdicts_republished_ = 0;
  std::optional<double> p_success_;
  std::string note_;
  std::optional<hal::TeamStatus> last_status_;
};

}  // namespace p3at::gate
