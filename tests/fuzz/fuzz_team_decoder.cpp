// libFuzzer target: the team link's authenticated decoders and the protocol
// that consumes them. Input: byte 0 picks the channel, the rest is the LCM
// payload. Any bytes must be safe (no crash, no leak, no UB), and:
//   - a payload is either counted once (malformed / a rejection) or accepted;
//   - a notification decoded with a valid tag re-encodes to exactly the input
//     (the encoding is canonical, so there is one authentic form per message);
//   - decoding what we encode gives back the same fields with a valid tag.
// Seeds: tests/fuzz/corpus/team (valid messages under the key below, with the
// launch session fields: a notification of another session, and verdicts GO,
// NO-GO and committed from alpha that echo bravo's nonce).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "p3at/team_link/team_protocol.hpp"
#include "p3at/team_link/team_wire.hpp"

namespace {

using namespace p3at::hal;

TeamKey fuzz_key() {
  TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(1 + i);
  return TeamKey(bytes);
}

void check(bool ok) {
  if (!ok) __builtin_trap();
}

std::uint64_t total(const TeamLinkStats& s) {
  return s.accepted + s.verdicts_accepted + s.telemetry_accepted + s.rejected_unknown_sender + s.rejected_bad_tag +
         s.rejected_replay + s.rejected_other_mission + s.rejected_other_session + s.malformed;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const TeamKey key = fuzz_key();
  const auto channel = static_cast<TeamChannel>(data[0] % 4);
  const std::span<const std::uint8_t> payload(data + 1, size - 1);

  switch (channel) {
    case TeamChannel::notify: {
      auto d = decode_notification(payload, key);
      if (d.ok()) {
        auto again = encode_notification(d->wire, key);
        check(again.ok());
        if (d->tag_ok) check(again.value() == std::vector<std::uint8_t>(payload.begin(), payload.end()));
        auto round = decode_notification(again.value(), key);
        check(round.ok() && round->tag_ok && round->wire.seq == d->wire.seq && round->wire.sender == d->wire.sender &&
              round->wire.recipients == d->wire.recipients);
      }
      break;
    }
    case TeamChannel::status: {
      auto d = decode_status(payload, key);
      if (d.ok()) {
        auto again = encode_status(d->wire, key);
        check(again.ok());
        if (d->tag_ok) check(again.value() == std::vector<std::uint8_t>(payload.begin(), payload.end()));
      }
      break;
    }
    case TeamChannel::telemetry: {
      auto d = decode_telemetry(payload, key);
      if (d.ok()) {
        auto again = encode_telemetry(d->wire, key);
        check(again.ok());
        if (d->tag_ok) check(again.value() == std::vector<std::uint8_t>(payload.begin(), payload.end()));
      }
      break;
    }
    case TeamChannel::gate: {
      auto d = decode_verdict(payload, key);
      if (d.ok()) {
        auto again = encode_verdict(d->wire, key);
        check(again.ok());
        if (d->tag_ok) check(again.value() == std::vector<std::uint8_t>(payload.begin(), payload.end()));
        auto round = decode_verdict(again.value(), key);
        check(round.ok() && round->tag_ok && round->wire.seq == d->wire.seq &&
              round->wire.verdict.robot == d->wire.verdict.robot &&
              round->wire.verdict.mission_hash == d->wire.verdict.mission_hash &&
              round->wire.verdict.decision == d->wire.verdict.decision &&
              round->wire.verdict.nonce == d->wire.verdict.nonce &&
              round->wire.verdict.session == d->wire.verdict.session &&
              round->wire.verdict.heard == d->wire.verdict.heard);
      }
      break;
    }
  }

  // The protocol end to end: bravo of team {alpha, bravo, charlie}.
  TeamLinkConfig config;
  config.mission_id = "fuzz-mission";
  config.self = "bravo";
  config.roster = {"alpha", "bravo", "charlie"};
  auto protocol = TeamProtocol::create(config, key);
  check(protocol.ok());
  std::vector<TeamNotification> delivered;
  std::vector<TeamDatagram> out;
  for (int round = 0; round < 2; ++round) {
    const auto before = total(protocol->stats());
    protocol->receive(round, channel, payload, delivered, out);
    const auto counted = total(protocol->stats()) - before;
    check(counted <= 1);
  }
  // The same bytes twice can be accepted at most once.
  check(delivered.size() <= 1);
  check(protocol->stats().accepted <= 1);
  check(protocol->stats().verdicts_accepted <= 1);
  check(protocol->stats().telemetry_accepted <= 1);
  return 0;
}
