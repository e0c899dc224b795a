// measure_messages(): one notification at a time over a simulated radio, both
// ends running the real team-link protocol (authentication, acks,
// retransmission every 200 ms). The sender sends at one of its cycles; the
// recipient reads the link, and so acknowledges, only at its own cycles; the
// sender reads the link at its cycles and whenever a datagram reaches it,
// so the acknowledgement's time is exact rather than rounded to a cycle (the
// verifier rounds delays to its own cycles).

#include "p3at/calibration_rig/calibrate_messages.hpp"

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "p3at/hal/team_key.hpp"
#include "p3at/hal/team_protocol.hpp"
#include "p3at/sim/rng.hpp"

namespace p3at::vipars {
namespace {

// Far beyond any delivery with retransmissions; a message not through by then is lost.
constexpr std::int64_t kGiveUpUs = 10'000'000;
// Between two notifications' send times in the log (each has its own radio).
constexpr std::int64_t kSpacingUs = 12'000'000;

// Inside one process the key's value is irrelevant; a fixed one keeps runs identical.
hal::TeamKey calibration_key() {
  hal::TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(0xC5 ^ (i * 11));
  return hal::TeamKey(bytes);
}

// Two robots on a radio of their own, for one notification: nothing left
// over from an earlier one (a late duplicate, its acknowledgement, the
// retransmissions of one never acknowledged) can be taken for this one's,
// and no third robot shares the broadcast medium.
struct Pair {
  std::unique_ptr<sim::SimRadio> radio;
  std::unique_ptr<sim::SimTeamLink> a;
  std::unique_ptr<sim::SimTeamLink> b;
};

Pair open_pair(const sim::RadioParams& params, const std::string& a, const std::string& b, std::uint64_t seed) {
  auto radio = sim::SimRadio::create(params, seed);
  if (!radio) throw std::runtime_error("radio: " + radio.error().message);
  Pair p;
  p.radio = std::move(radio).value();
  const auto link = [&](const std::string& self) {
    hal::TeamLinkConfig config;
    config.mission_id = "calibration";
    config.self = self;
    config.roster = {a, b};
    auto l = sim::SimTeamLink::create(*p.radio, config, calibration_key());
    if (!l) throw std::runtime_error("team link: " + l.error().message);
    return std::move(l).value();
  };
  p.a = link(a);
  p.b = link(b);
  return p;
}

// Times one notification from `sender` to `recipient`, starting at `t0_us`.
verifier::MessageRow time_one(sim::SimRadio& radio, sim::SimTeamLink& sender, sim::SimTeamLink& recipient,
                              const std::string& sender_name, const std::string& recipient_name, std::int64_t t0_us,
                              std::int64_t cycle_us, std::int64_t phase_us) {
  std::vector<hal::TeamNotification> inbox;
  (void)sender.poll(t0_us, inbox);
  const Result<std::uint64_t> seq = sender.notify("calibration_ping", {recipient_name});
  if (!seq) throw std::runtime_error("team link: " + seq.error().message);
  verifier::MessageRow row;
  row.sender = sender_name;
  row.sent_s = static_cast<double>(t0_us) / 1e6;
  std::int64_t sender_cycle = t0_us + cycle_us;
  std::int64_t recipient_cycle = t0_us + (phase_us > 0 ? phase_us : cycle_us);
  while (true) {
    std::int64_t t = std::min(sender_cycle, recipient_cycle);
    const std::optional<std::int64_t> to_sender = radio.next_arrival_us(sender.endpoint());
    if (to_sender) t = std::min(t, std::max(*to_sender, t0_us));
    if (t - t0_us > kGiveUpUs) break;
    // Only the sender's copies travel to the recipient: the first to arrive is the delivery.
    if (!row.delivered_s) {
      const std::optional<std::int64_t> to_recipient = radio.next_arrival_us(recipient.endpoint());
      if (to_recipient && *to_recipient <= t) row.delivered_s = static_cast<double>(*to_recipient) / 1e6;
    }
    if (t == recipient_cycle) {
      (void)recipient.poll(t, inbox);
      recipient_cycle += cycle_us;
    }
    if (t == sender_cycle || (to_sender && t == *to_sender)) {
      (void)sender.poll(t, inbox);
      if (t == sender_cycle) sender_cycle += cycle_us;
      if (sender.acknowledged(seq.value())) {
        row.acked_s = static_cast<double>(t) / 1e6;
        break;
      }
    }
  }
  return row;
}

}  // namespace

std::vector<verifier::MessageRow> measure_messages(const sim::RadioParams& radio, const std::vector<std::string>& robots,
                                                   const MessagePlan& plan, std::uint64_t seed) {
  std::vector<std::string> names = robots;
  if (names.size() == 1) names.push_back(names.front() == "teammate" ? "teammate2" : "teammate");
  // Every ordered pair in turn.
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& a : names) {
    for (const std::string& b : names) {
      if (a != b) pairs.emplace_back(a, b);
    }
  }
  const auto cycle_us = static_cast<std::int64_t>(plan.cycle_s * 1e6);
  sim::Rng phase_rng(seed, 0xCA11B);
  std::vector<verifier::MessageRow> rows;
  for (std::size_t k = 0; k < plan.count; ++k) {
    const auto& [from, to] = pairs[k % pairs.size()];
    Pair p = open_pair(radio, from, to, seed * 1000003ULL + k);
    const auto t0 = static_cast<std::int64_t>(k + 1) * kSpacingUs;
    const std::int64_t phase =
        plan.random_phase ? static_cast<std::int64_t>(phase_rng.uniform() * static_cast<double>(cycle_us)) : 0;
    verifier::MessageRow row = time_one(*p.radio, *p.a, *p.b, from, to, t0, cycle_us, phase);
    row.id = static_cast<std::int64_t>(k);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace p3at::vipars
