#pragma once
/// The team link's messages on the wire: the LCM types of package p3at_lcm
/// (protocols/lcm/*.lcm), each authenticated with the team key. Pure: no I/O,
/// shared by the LCM backend, the simulated radio, tests and fuzzers.
///
/// Authentication: tag = crypto_auth (HMAC-SHA512-256, libsodium) with the
/// team key over the message's LCM encoding (fingerprint included) with
/// tag_len = 0 and no tag bytes; the sent message carries tag_len = 32 and the
/// tag. See docs/team-link.md.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/team_key.hpp"
#include "p3at/hal/team_link.hpp"

namespace p3at::hal {

/// The team link's LCM channels.
enum class TeamChannel : std::uint8_t { notify = 0, telemetry = 1, status = 2, gate = 3 };

inline constexpr std::string_view kNotifyChannel = "P3AT_NOTIFY";        ///< p3at_lcm.notification_t
inline constexpr std::string_view kTelemetryChannel = "P3AT_TELEMETRY";  ///< p3at_lcm.telemetry_t
inline constexpr std::string_view kStatusChannel = "P3AT_STATUS";        ///< p3at_lcm.mission_status_t
inline constexpr std::string_view kGateChannel = "P3AT_GATE";            ///< p3at_lcm.gate_verdict_t

/// The LCM channel name of a channel.
std::string_view channel_name(TeamChannel channel);
/// Inverse of channel_name; nullopt for any other channel.
std::optional<TeamChannel> channel_from_name(std::string_view name);

/// One encoded message and the channel it travels on.
struct TeamDatagram {
  TeamChannel channel = TeamChannel::notify;
  std::vector<std::uint8_t> bytes;
};

/// Limits that encoders enforce (invalid_argument) and decoders check (malformed).
/// Strings are bytes without NUL; limits are in bytes.
inline constexpr std::size_t kMaxTeamNameBytes = 64;    ///< robot names and the mission id
inline constexpr std::size_t kMaxTeamMessageBytes = 128;  ///< a notification's message name
inline constexpr std::size_t kMaxTeamTextBytes = 256;   ///< phase, state, reason
inline constexpr std::size_t kMaxTeamRecipients = 32;
inline constexpr std::size_t kTeamTagBytes = 32;        ///< crypto_auth_BYTES
inline constexpr std::size_t kMissionHashHexDigits = 64;  ///< a gate verdict's mission_hash: BLAKE2b-256 in hex
inline constexpr std::size_t kSessionHexDigits = 64;      ///< a session id: BLAKE2b-256 in hex ("" before launch)
inline constexpr std::size_t kGateNonceHexDigits = 32;    ///< a gate nonce: 16 random bytes in hex

/// True for exactly `digits` lowercase hexadecimal digits.
bool is_lower_hex(std::string_view text, std::size_t digits);

/// p3at_lcm.notification_t, as our code sees it.
struct NotificationWire {
  std::int64_t utime_us = 0;  ///< sender's clock when sent (informational)
  std::string mission_id;
  std::string session;        ///< "" or 64 lowercase hex digits
  std::string sender;
  std::uint64_t seq = 0;      ///< < 2^63; 0 in an acknowledgement
  std::string message;
  bool is_ack = false;
  std::string ack_sender;     ///< acknowledgement only
  std::uint64_t ack_seq = 0;  ///< acknowledgement only, < 2^63
  std::vector<std::string> recipients;  ///< notification only
};

/// p3at_lcm.mission_status_t.
struct StatusWire {
  std::int64_t utime_us = 0;
  std::string mission_id;
  std::string session;
  std::uint64_t seq = 0;  ///< < 2^63
  TeamStatus status;      ///< status.robot is the sender; p_success must be finite
};

/// p3at_lcm.telemetry_t.
struct TelemetryWire {
  std::int64_t utime_us = 0;
  std::string mission_id;
  std::string session;
  std::uint64_t seq = 0;  ///< < 2^63; counters of `telemetry` must be < 2^63 too
  Telemetry telemetry;    ///< telemetry.robot is the sender
};

/// p3at_lcm.gate_verdict_t.
struct VerdictWire {
  std::int64_t utime_us = 0;
  std::string mission_id;
  std::uint64_t seq = 0;  ///< < 2^63
  GateVerdict verdict;    ///< verdict.robot is the sender; mission_hash is 64 lowercase hex
                          ///< digits, detail at most kMaxTeamTextBytes; every number finite;
                          ///< nonce 32 lowercase hex digits, session "" or 64, at most
                          ///< kMaxTeamRecipients heard entries, each a name and a nonce
};

/// A decoded message and whether its tag verified under the key (false for a
/// wrong, truncated or missing tag). Callers decide what to check first.
template <class Wire>
struct Verified {
  Wire wire;
  bool tag_ok = false;
};

/// Encodes and tags. invalid_argument when a field breaks a limit above.
Result<std::vector<std::uint8_t>> encode_notification(const NotificationWire& wire, const TeamKey& key);
Result<std::vector<std::uint8_t>> encode_status(const StatusWire& wire, const TeamKey& key);
Result<std::vector<std::uint8_t>> encode_telemetry(const TelemetryWire& wire, const TeamKey& key);
Result<std::vector<std::uint8_t>> encode_verdict(const VerdictWire& wire, const TeamKey& key);

/// Decodes and verifies. Error::Code::protocol ("malformed") when the bytes are
/// not exactly one well-formed message of that type within the limits above
/// (wrong fingerprint, truncated, trailing bytes, bad lengths, NUL in a string,
/// boolean other than 0/1, negative sequence number, non-finite p_success; for
/// a verdict also a decision other than GO / NO-GO / OVERRIDE, a mission_hash
/// that is not 64 lowercase hex digits, or a non-finite number).
/// Never throws and never reads outside `bytes`, whatever they hold.
Result<Verified<NotificationWire>> decode_notification(std::span<const std::uint8_t> bytes, const TeamKey& key);
Result<Verified<StatusWire>> decode_status(std::span<const std::uint8_t> bytes, const TeamKey& key);
Result<Verified<TelemetryWire>> decode_telemetry(std::span<const std::uint8_t> bytes, const TeamKey& key);
Result<Verified<VerdictWire>> decode_verdict(std::span<const std::uint8_t> bytes, const TeamKey& key);

}  // namespace p3at::hal
