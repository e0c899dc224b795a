#include "p3at/hal/team_wire.hpp"

#include <sodium.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "p3at_lcm/gate_verdict_t.hpp"
#include "p3at_lcm/mission_status_t.hpp"
#include "p3at_lcm/notification_t.hpp"
#include "p3at_lcm/telemetry_t.hpp"
#include "team_wire_check.hpp"

namespace p3at::hal {

static_assert(kTeamTagBytes == crypto_auth_BYTES);
static_assert(TeamKey::kBytes == crypto_auth_KEYBYTES);

namespace {

constexpr std::uint64_t kMaxWireUnsigned = static_cast<std::uint64_t>(INT64_MAX);

bool is_mission_hash(const std::string& text) { return is_lower_hex(text, kMissionHashHexDigits); }

bool is_session(const std::string& text) { return text.empty() || is_lower_hex(text, kSessionHexDigits); }

bool all_finite(std::initializer_list<double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

Error malformed(std::string_view type, std::string_view what) {
  return make_error(Error::Code::protocol, "malformed " + std::string(type) + ": " + std::string(what));
}

// Collects the first limit a message breaks, as the encoders' error.
class FieldCheck {
 public:
  explicit FieldCheck(std::string_view type) : type_(type) {}

  void text(std::string_view field, const std::string& value, std::size_t max_bytes) {
    if (!error_.empty()) return;
    if (value.size() > max_bytes) {
      error_ = std::string(field) + " is " + std::to_string(value.size()) + " bytes (at most " +
               std::to_string(max_bytes) + ")";
    } else if (value.find('\0') != std::string::npos) {
      error_ = std::string(field) + " contains a NUL byte";
    }
  }
  void count(std::string_view field, std::uint64_t value) {
    if (error_.empty() && value > kMaxWireUnsigned) error_ = std::string(field) + " is 2^63 or more";
  }
  void condition(bool ok, std::string_view what) {
    if (error_.empty() && !ok) error_ = what;
  }
  Status result() const {
    if (error_.empty()) return {};
    return make_error(Error::Code::invalid_argument, "cannot encode " + type_ + ": " + error_);
  }

 private:
  std::string type_;
  std::string error_;
};

bool sodium_ready() {
  static const bool ready = sodium_init() >= 0;
  return ready;
}

template <class Msg>
std::vector<std::uint8_t> encode_raw(const Msg& msg) {
  const int size = msg.getEncodedSize();
  std::vector<std::uint8_t> out(static_cast<std::size_t>(size));
  // Cannot fail: the buffer has exactly the size the message reports.
  (void)msg.encode(out.data(), 0, size);
  return out;
}

template <class Msg>
Result<std::vector<std::uint8_t>> encode_tagged(Msg msg, const TeamKey& key) {
  if (!sodium_ready()) return make_error(Error::Code::io, "libsodium failed to initialise");
  msg.tag_len = 0;
  msg.tag.clear();
  const std::vector<std::uint8_t> untagged = encode_raw(msg);
  std::vector<std::uint8_t> tag(kTeamTagBytes);
  crypto_auth(tag.data(), untagged.data(), untagged.size(), key.bytes().data());
  msg.tag_len = static_cast<std::int16_t>(kTeamTagBytes);
  msg.tag = std::move(tag);
  return encode_raw(msg);
}

// True when the message's tag is the team key's tag of its untagged encoding.
template <class Msg>
bool tag_verifies(Msg msg, const TeamKey& key) {
  if (!sodium_ready()) return false;
  if (msg.tag_len != static_cast<std::int16_t>(kTeamTagBytes) || msg.tag.size() != kTeamTagBytes) return false;
  const std::vector<std::uint8_t> tag = std::move(msg.tag);
  msg.tag.clear();
  msg.tag_len = 0;
  const std::vector<std::uint8_t> untagged = encode_raw(msg);
  return crypto_auth_verify(tag.data(), untagged.data(), untagged.size(), key.bytes().data()) == 0;
}

// Runs the layout check, then lcm-gen's decoder, which must consume every byte.
template <class Msg>
bool decode_checked(std::span<const std::uint8_t> bytes, bool (*layout_ok)(std::span<const std::uint8_t>, std::int64_t),
                    Msg& msg) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) return false;
  if (!layout_ok(bytes, Msg::getHash())) return false;
  const int size = static_cast<int>(bytes.size());
  return msg.decode(bytes.data(), 0, size) == size;
}

}  // namespace

bool is_lower_hex(std::string_view text, std::size_t digits) {
  if (text.size() != digits) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

std::string_view channel_name(TeamChannel channel) {
  switch (channel) {
    case TeamChannel::notify: return kNotifyChannel;
    case TeamChannel::telemetry: return kTelemetryChannel;
    case TeamChannel::status: return kStatusChannel;
    case TeamChannel::gate: return kGateChannel;
  }
  return "?";
}

std::optional<TeamChannel> channel_from_name(std::string_view name) {
  if (name == kNotifyChannel) return TeamChannel::notify;
  if (name == kTelemetryChannel) return TeamChannel::telemetry;
  if (name == kStatusChannel) return TeamChannel::status;
  if (name == kGateChannel) return TeamChannel::gate;
  return std::nullopt;
}

Result<std::vector<std::uint8_t>> encode_notification(const NotificationWire& wire, const TeamKey& key) {
  FieldCheck check("notification");
  check.text("mission_id", wire.mission_id, kMaxTeamNameBytes);
  check.text("sender", wire.sender, kMaxTeamNameBytes);
  check.text("message", wire.message, kMaxTeamMessageBytes);
  check.text("ack_sender", wire.ack_sender, kMaxTeamNameBytes);
  check.count("seq", wire.seq);
  check.count("ack_seq", wire.ack_seq);
  check.condition(is_session(wire.session), "session is neither empty nor 64 lowercase hexadecimal digits");
  check.condition(wire.recipients.size() <= kMaxTeamRecipients, "more than 32 recipients");
  for (const auto& r : wire.recipients) check.text("recipient", r, kMaxTeamNameBytes);
  if (auto s = check.result(); !s) return s.error();

  p3at_lcm::notification_t msg;
  msg.utime = wire.utime_us;
  msg.mission_id = wire.mission_id;
  msg.session = wire.session;
  msg.sender = wire.sender;
  msg.seq = static_cast<std::int64_t>(wire.seq);
  msg.message = wire.message;
  msg.is_ack = wire.is_ack ? 1 : 0;
  msg.ack_sender = wire.ack_sender;
  msg.ack_seq = static_cast<std::int64_t>(wire.ack_seq);
  msg.num_recipients = static_cast<std::int16_t>(wire.recipients.size());
  msg.recipients = wire.recipients;
  return encode_tagged(std::move(msg), key);
}

Result<std::vector<std::uint8_t>> encode_status(const StatusWire& wire, const TeamKey& key) {
  FieldCheck check("status");
  check.text("mission_id", wire.mission_id, kMaxTeamNameBytes);
  check.text("robot", wire.status.robot, kMaxTeamNameBytes);
  check.text("phase", wire.status.phase, kMaxTeamTextBytes);
  check.text("state", wire.status.state, kMaxTeamTextBytes);
  check.text("reason", wire.status.reason, kMaxTeamTextBytes);
  check.count("seq", wire.seq);
  check.condition(std::isfinite(wire.status.p_success), "p_success is not finite");
  check.condition(is_session(wire.session), "session is neither empty nor 64 lowercase hexadecimal digits");
  if (auto s = check.result(); !s) return s.error();

  p3at_lcm::mission_status_t msg;
  msg.utime = wire.utime_us;
  msg.mission_id = wire.mission_id;
  msg.session = wire.session;
  msg.robot = wire.status.robot;
  msg.seq = static_cast<std::int64_t>(wire.seq);
  msg.phase = wire.status.phase;
  msg.state = wire.status.state;
  msg.reason = wire.status.reason;
  msg.p_success = wire.status.p_success;
  return encode_tagged(std::move(msg), key);
}

Result<std::vector<std::uint8_t>> encode_telemetry(const TelemetryWire& wire, const TeamKey& key) {
  const Telemetry& t = wire.telemetry;
  FieldCheck check("telemetry");
  check.text("mission_id", wire.mission_id, kMaxTeamNameBytes);
  check.text("robot", t.robot, kMaxTeamNameBytes);
  check.text("state", t.state, kMaxTeamTextBytes);
  check.count("seq", wire.seq);
  check.count("cycles", t.cycles);
  check.count("overruns", t.overruns);
  check.count("missed_updates", t.missed_updates);
  check.condition(is_session(wire.session), "session is neither empty nor 64 lowercase hexadecimal digits");
  if (auto s = check.result(); !s) return s.error();

  p3at_lcm::telemetry_t msg;
  msg.utime = wire.utime_us;
  msg.mission_id = wire.mission_id;
  msg.session = wire.session;
  msg.robot = t.robot;
  msg.seq = static_cast<std::int64_t>(wire.seq);
  msg.state = t.state;
  msg.pose.x_m = t.x_m;
  msg.pose.y_m = t.y_m;
  msg.pose.theta_rad = t.theta_rad;
  msg.trans_vel_mps = t.trans_vel_mps;
  msg.rot_vel_radps = t.rot_vel_radps;
  msg.cycle.cycles = static_cast<std::int64_t>(t.cycles);
  msg.cycle.overruns = static_cast<std::int64_t>(t.overruns);
  msg.cycle.missed_updates = static_cast<std::int64_t>(t.missed_updates);
  msg.cycle.p50_us = t.cycle_p50_us;
  msg.cycle.p99_us = t.cycle_p99_us;
  return encode_tagged(std::move(msg), key);
}

Result<std::vector<std::uint8_t>> encode_verdict(const VerdictWire& wire, const TeamKey& key) {
  const GateVerdict& v = wire.verdict;
  FieldCheck check("gate verdict");
  check.text("mission_id", wire.mission_id, kMaxTeamNameBytes);
  check.text("robot", v.robot, kMaxTeamNameBytes);
  check.text("detail", v.detail, kMaxTeamTextBytes);
  check.count("seq", wire.seq);
  check.condition(is_mission_hash(v.mission_hash), "mission_hash is not 64 lowercase hexadecimal digits");
  check.condition(all_finite({v.p_time, v.p_radius, v.p_joint, v.threshold, v.tmax_s, v.rmax_m}),
                  "a probability or criterion is not finite");
  check.condition(is_lower_hex(v.nonce, kGateNonceHexDigits), "nonce is not 32 lowercase hexadecimal digits");
  check.condition(is_session(v.session), "session is neither empty nor 64 lowercase hexadecimal digits");
  check.condition(v.heard.size() <= kMaxTeamRecipients, "more than 32 heard nonces");
  for (const HeardNonce& h : v.heard) {
    check.text("heard robot", h.robot, kMaxTeamNameBytes);
    check.condition(is_lower_hex(h.nonce, kGateNonceHexDigits), "a heard nonce is not 32 lowercase hexadecimal digits");
  }
  if (auto s = check.result(); !s) return s.error();

  p3at_lcm::gate_verdict_t msg;
  msg.utime = wire.utime_us;
  msg.mission_id = wire.mission_id;
  msg.robot = v.robot;
  msg.seq = static_cast<std::int64_t>(wire.seq);
  msg.mission_hash = v.mission_hash;
  msg.decision = to_string(v.decision);
  msg.p_time = v.p_time;
  msg.p_radius = v.p_radius;
  msg.p_joint = v.p_joint;
  msg.threshold = v.threshold;
  msg.tmax_s = v.tmax_s;
  msg.rmax_m = v.rmax_m;
  msg.detail = v.detail;
  msg.nonce = v.nonce;
  msg.session = v.session;
  msg.num_heard = static_cast<std::int16_t>(v.heard.size());
  for (const HeardNonce& h : v.heard) {
    msg.heard_robot.push_back(h.robot);
    msg.heard_nonce.push_back(h.nonce);
  }
  return encode_tagged(std::move(msg), key);
}

Result<Verified<NotificationWire>> decode_notification(std::span<const std::uint8_t> bytes, const TeamKey& key) {
  p3at_lcm::notification_t msg;
  if (!decode_checked(bytes, &wire_check::notification_layout_ok, msg)) {
    return malformed("notification", "not a well-formed p3at_lcm.notification_t");
  }
  if (!is_session(msg.session)) return malformed("notification", "session is not empty or 64 lowercase hex digits");
  Verified<NotificationWire> out;
  NotificationWire& w = out.wire;
  w.utime_us = msg.utime;
  w.mission_id = msg.mission_id;
  w.session = msg.session;
  w.sender = msg.sender;
  w.seq = static_cast<std::uint64_t>(msg.seq);
  w.message = msg.message;
  w.is_ack = msg.is_ack != 0;
  w.ack_sender = msg.ack_sender;
  w.ack_seq = static_cast<std::uint64_t>(msg.ack_seq);
  w.recipients = msg.recipients;
  out.tag_ok = tag_verifies(std::move(msg), key);
  return out;
}

Result<Verified<StatusWire>> decode_status(std::span<const std::uint8_t> bytes, const TeamKey& key) {
  p3at_lcm::mission_status_t msg;
  if (!decode_checked(bytes, &wire_check::status_layout_ok, msg)) {
    return malformed("status", "not a well-formed p3at_lcm.mission_status_t");
  }
  if (!std::isfinite(msg.p_success)) return malformed("status", "p_success is not finite");
  if (!is_session(msg.session)) return malformed("status", "session is not empty or 64 lowercase hex digits");
  Verified<StatusWire> out;
  StatusWire& w = out.wire;
  w.utime_us = msg.utime;
  w.mission_id = msg.mission_id;
  w.session = msg.session;
  w.seq = static_cast<std::uint64_t>(msg.seq);
  w.status.robot = msg.robot;
  w.status.phase = msg.phase;
  w.status.state = msg.state;
  w.status.reason = msg.reason;
  w.status.p_success = msg.p_success;
  out.tag_ok = tag_verifies(std::move(msg), key);
  return out;
}

Result<Verified<TelemetryWire>> decode_telemetry(std::span<const std::uint8_t> bytes, const TeamKey& key) {
  p3at_lcm::telemetry_t msg;
  if (!decode_checked(bytes, &wire_check::telemetry_layout_ok, msg)) {
    return malformed("telemetry", "not a well-formed p3at_lcm.telemetry_t");
  }
  if (!is_session(msg.session)) return malformed("telemetry", "session is not empty or 64 lowercase hex digits");
  Verified<TelemetryWire> out;
  TelemetryWire& w = out.wire;
  Telemetry& t = w.telemetry;
  w.utime_us = msg.utime;
  w.mission_id = msg.mission_id;
  w.session = msg.session;
  w.seq = static_cast<std::uint64_t>(msg.seq);
  t.robot = msg.robot;
  t.state = msg.state;
  t.x_m = msg.pose.x_m;
  t.y_m = msg.pose.y_m;
  t.theta_rad = msg.pose.theta_rad;
  t.trans_vel_mps = msg.trans_vel_mps;
  t.rot_vel_radps = msg.rot_vel_radps;
  t.cycles = static_cast<std::uint64_t>(msg.cycle.cycles);
  t.overruns = static_cast<std::uint64_t>(msg.cycle.overruns);
  t.missed_updates = static_cast<std::uint64_t>(msg.cycle.missed_updates);
  t.cycle_p50_us = msg.cycle.p50_us;
  t.cycle_p99_us = msg.cycle.p99_us;
  out.tag_ok = tag_verifies(std::move(msg), key);
  return out;
}

Result<Verified<VerdictWire>> decode_verdict(std::span<const std::uint8_t> bytes, const TeamKey& key) {
  p3at_lcm::gate_verdict_t msg;
  if (!decode_checked(bytes, &wire_check::verdict_layout_ok, msg)) {
    return malformed("gate verdict", "not a well-formed p3at_lcm.gate_verdict_t");
  }
  const std::optional<GateDecision> decision = gate_decision_from_string(msg.decision);
  if (!decision) return malformed("gate verdict", "decision is not GO, NO-GO or OVERRIDE");
  if (!is_mission_hash(msg.mission_hash)) {
    return malformed("gate verdict", "mission_hash is not 64 lowercase hexadecimal digits");
  }
  if (!all_finite({msg.p_time, msg.p_radius, msg.p_joint, msg.threshold, msg.tmax_s, msg.rmax_m})) {
    return malformed("gate verdict", "a probability or criterion is not finite");
  }
  if (!is_lower_hex(msg.nonce, kGateNonceHexDigits)) return malformed("gate verdict", "nonce is not 32 lowercase hex digits");
  if (!is_session(msg.session)) return malformed("gate verdict", "session is not empty or 64 lowercase hex digits");
  for (const std::string& n : msg.heard_nonce) {
    if (!is_lower_hex(n, kGateNonceHexDigits)) return malformed("gate verdict", "a heard nonce is not 32 lowercase hex digits");
  }
  Verified<VerdictWire> out;
  VerdictWire& w = out.wire;
  GateVerdict& v = w.verdict;
  w.utime_us = msg.utime;
  w.mission_id = msg.mission_id;
  w.seq = static_cast<std::uint64_t>(msg.seq);
  v.robot = msg.robot;
  v.mission_hash = msg.mission_hash;
  v.decision = *decision;
  v.p_time = msg.p_time;
  v.p_radius = msg.p_radius;
  v.p_joint = msg.p_joint;
  v.threshold = msg.threshold;
  v.tmax_s = msg.tmax_s;
  v.rmax_m = msg.rmax_m;
  v.detail = msg.detail;
  v.nonce = msg.nonce;
  v.session = msg.session;
  for (std::size_t i = 0; i < msg.heard_robot.size(); ++i) v.heard.push_back({msg.heard_robot[i], msg.heard_nonce[i]});
  out.tag_ok = tag_verifies(std::move(msg), key);
  return out;
}

}  // namespace p3at::hal
