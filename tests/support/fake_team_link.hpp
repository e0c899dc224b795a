#pragma once
// An in-process hal::TeamLink for unit tests. Links joined with connect() form
// a perfect radio: notify() puts the notification in each recipient's inbox,
// the recipient's next poll() delivers it and (with auto_ack) acknowledges it
// to the sender at once; publish_status() updates every peer's
// teammate_status(), publish_verdict() every peer's teammate_verdicts() and
// publish_telemetry() every peer's teammate_telemetry(). A lone link is driven
// by the test: deliver(), ack(), set_teammate_status(), set_teammate_verdict(),
// set_teammate_telemetry(). Every call is recorded.

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/team_link.hpp"

namespace p3at::test {

class FakeTeamLink final : public hal::TeamLink {
 public:
  struct NotifyCall {
    std::string message;
    std::vector<std::string> recipients;
    std::uint64_t seq = 0;
  };

  explicit FakeTeamLink(std::string self) : self_(std::move(self)) {}

  /// Joins two links both ways (a perfect radio between them).
  static void connect(FakeTeamLink& a, FakeTeamLink& b) {
    a.peers_.push_back(&b);
    b.peers_.push_back(&a);
  }

  // ---- hal::TeamLink
  Result<std::uint64_t> notify(const std::string& message, const std::vector<std::string>& recipients) override {
    if (fail_notify) return make_error(Error::Code::state, "fake team link: notify refused by the test");
    const std::uint64_t seq = next_seq_++;
    notify_calls.push_back(NotifyCall{message, recipients, seq});
    waiting_[seq] = recipients;
    for (FakeTeamLink* peer : peers_) {
      if (std::find(recipients.begin(), recipients.end(), peer->self_) != recipients.end()) {
        peer->inbox_.push_back(Incoming{hal::TeamNotification{self_, message, seq}, this});
      }
    }
    return seq;
  }
  bool acknowledged(std::uint64_t seq) const override {
    const auto it = waiting_.find(seq);
    return it != waiting_.end() && it->second.empty();
  }
  Status poll(std::int64_t now_us, std::vector<hal::TeamNotification>& received) override {
    ++poll_calls;
    last_poll_us = now_us;
    std::vector<Incoming> arrived;
    arrived.swap(inbox_);
    for (const Incoming& in : arrived) {
      received.push_back(in.notification);
      if (auto_ack && in.from != nullptr) in.from->ack(in.notification.seq, self_);
    }
    if (poll_error) return make_error(Error::Code::io, "fake team link: poll error set by the test");
    return {};
  }
  Status publish_telemetry(const hal::Telemetry& telemetry) override {
    telemetry_sent.push_back(telemetry);
    hal::Telemetry stamped = telemetry;
    stamped.robot = self_;
    for (FakeTeamLink* peer : peers_) peer->set_teammate_telemetry(stamped);
    return {};
  }
  Status publish_status(const hal::TeamStatus& status) override {
    status_sent.push_back(status);
    for (FakeTeamLink* peer : peers_) peer->set_teammate_status(status);
    return {};
  }
  const std::vector<hal::TeamStatus>& teammate_status() const override { return teammates_; }
  Status publish_verdict(const hal::GateVerdict& verdict) override {
    if (fail_publish_verdict) return make_error(Error::Code::io, "fake team link: verdict refused by the test");
    verdicts_sent.push_back(verdict);
    hal::GateVerdict stamped = verdict;
    stamped.robot = self_;
    for (FakeTeamLink* peer : peers_) peer->set_teammate_verdict(stamped);
    return {};
  }
  const std::vector<hal::GateVerdict>& teammate_verdicts() const override { return verdicts_; }
  const std::vector<hal::Telemetry>& teammate_telemetry() const override { return telemetry_; }
  const hal::TeamLinkStats& stats() const override { return stats_; }
  void set_session(const std::string& session) override { session_ = session; }
  const std::string& session() const override { return session_; }
  std::optional<std::int64_t> last_heard_us(const std::string& robot) const override {
    const auto it = last_heard_.find(robot);
    if (it == last_heard_.end()) return std::nullopt;
    return it->second;
  }

  // ---- test controls
  /// Sets when `robot` was last heard from (liveness tests).
  void set_last_heard(const std::string& robot, std::int64_t at_us) { last_heard_[robot] = at_us; }
  /// Queues a notification for the next poll(), as if `sender` had sent it.
  void deliver(const std::string& sender, const std::string& message, std::uint64_t seq = 1) {
    inbox_.push_back(Incoming{hal::TeamNotification{sender, message, seq}, nullptr});
  }
  /// Records that `recipient` acknowledged our notification `seq`.
  void ack(std::uint64_t seq, const std::string& recipient) {
    auto it = waiting_.find(seq);
    if (it == waiting_.end()) return;
    std::erase(it->second, recipient);
  }
  void ack_all(std::uint64_t seq) {
    auto it = waiting_.find(seq);
    if (it != waiting_.end()) it->second.clear();
  }
  /// Replaces (or adds) a teammate's latest status.
  void set_teammate_status(const hal::TeamStatus& status) { replace_or_add(teammates_, status); }
  /// Replaces (or adds) a teammate's latest gate verdict.
  void set_teammate_verdict(const hal::GateVerdict& verdict) { replace_or_add(verdicts_, verdict); }
  /// Replaces (or adds) a teammate's latest telemetry.
  void set_teammate_telemetry(const hal::Telemetry& telemetry) { replace_or_add(telemetry_, telemetry); }
  const std::string& self() const { return self_; }
  hal::TeamLinkStats& stats_for_test() { return stats_; }

  bool auto_ack = true;
  bool fail_notify = false;
  bool poll_error = false;
  bool fail_publish_verdict = false;
  int poll_calls = 0;
  std::int64_t last_poll_us = 0;
  std::vector<NotifyCall> notify_calls;
  std::vector<hal::Telemetry> telemetry_sent;
  std::vector<hal::TeamStatus> status_sent;
  std::vector<hal::GateVerdict> verdicts_sent;

 private:
  struct Incoming {
    hal::TeamNotification notification;
    FakeTeamLink* from = nullptr;
  };

  template <class Item>
  static void replace_or_add(std::vector<Item>& held, const Item& item) {
    const auto it = std::find_if(held.begin(), held.end(), [&](const Item& h) { return h.robot == item.robot; });
    if (it == held.end()) {
      held.push_back(item);
    } else {
      *it = item;
    }
  }

  std::string self_;
  std::vector<FakeTeamLink*> peers_;
  std::vector<Incoming> inbox_;
  std::map<std::uint64_t, std::vector<std::string>> waiting_;
  std::vector<hal::TeamStatus> teammates_;
  std::vector<hal::GateVerdict> verdicts_;
  std::vector<hal::Telemetry> telemetry_;
  std::uint64_t next_seq_ = 1;
  hal::TeamLinkStats stats_;
  std::string session_;
  std::map<std::string, std::int64_t> last_heard_;
};

}  // namespace p3at::test
