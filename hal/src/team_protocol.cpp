#include "p3at/hal/team_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace p3at::hal {

namespace {

constexpr std::uint64_t kMaxFirstSeq = std::uint64_t{1} << 62;

Status check_name(std::string_view field, const std::string& value, std::size_t max_bytes) {
  if (value.empty()) return make_error(Error::Code::invalid_argument, "team link: " + std::string(field) + " is empty");
  if (value.size() > max_bytes) {
    return make_error(Error::Code::invalid_argument, "team link: " + std::string(field) + " '" + value + "' is longer than " +
                                                         std::to_string(max_bytes) + " bytes");
  }
  if (value.find('\0') != std::string::npos) {
    return make_error(Error::Code::invalid_argument, "team link: " + std::string(field) + " contains a NUL byte");
  }
  return {};
}

std::string cut(const std::string& text) { return text.size() <= kMaxTeamTextBytes ? text : text.substr(0, kMaxTeamTextBytes); }

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

Status validate_team_link_config(const TeamLinkConfig& config) {
  if (auto s = check_name("mission id", config.mission_id, kMaxTeamNameBytes); !s) return s;
  if (auto s = check_name("robot name (self)", config.self, kMaxTeamNameBytes); !s) return s;
  std::set<std::string> seen;
  for (const auto& name : config.roster) {
    if (auto s = check_name("roster name", name, kMaxTeamNameBytes); !s) return s;
    if (!seen.insert(name).second) {
      return make_error(Error::Code::invalid_argument, "team link: roster names '" + name + "' twice");
    }
  }
  if (seen.count(config.self) == 0) {
    return make_error(Error::Code::invalid_argument, "team link: this robot '" + config.self + "' is not in the roster");
  }
  if (config.retransmit_interval_us <= 0) {
    return make_error(Error::Code::invalid_argument, "team link: retransmit interval must be > 0 us");
  }
  if (config.max_unacknowledged == 0) {
    return make_error(Error::Code::invalid_argument, "team link: max_unacknowledged must be >= 1");
  }
  if (config.first_seq == 0 || config.first_seq >= kMaxFirstSeq) {
    return make_error(Error::Code::invalid_argument, "team link: first_seq must be in [1, 2^62)");
  }
  return {};
}

Result<TeamProtocol> TeamProtocol::create(TeamLinkConfig config, const TeamKey& key) {
  if (auto s = validate_team_link_config(config); !s) return s.error();
  return TeamProtocol(std::move(config), key);
}

TeamProtocol::TeamProtocol(TeamLinkConfig config, const TeamKey& key)
    : config_(std::move(config)),
      key_(key),
      next_notify_seq_(config_.first_seq),
      next_status_seq_(config_.first_seq),
      next_telemetry_seq_(config_.first_seq),
      next_verdict_seq_(config_.first_seq) {}

void TeamProtocol::note_time(std::int64_t now_us) {
  if (!now_us_ || now_us > *now_us_) now_us_ = now_us;
}

std::int64_t TeamProtocol::utime() const { return now_us_.value_or(0) + config_.utime_offset_us; }

bool TeamProtocol::in_roster(const std::string& name) const { return contains(config_.roster, name); }

Result<std::uint64_t> TeamProtocol::notify(const std::string& message, const std::vector<std::string>& recipients,
                                           std::vector<TeamDatagram>& out) {
  if (auto s = check_name("message name", message, kMaxTeamMessageBytes); !s) return s.error();
  for (std::size_t i = 0; i < recipients.size(); ++i) {
    const std::string& r = recipients[i];
    if (r == config_.self) {
      return make_error(Error::Code::invalid_argument, "team link: '" + message + "': a robot cannot notify itself");
    }
    if (!in_roster(r)) {
      return make_error(Error::Code::invalid_argument,
                        "team link: '" + message + "': recipient '" + r + "' is not in the team roster");
    }
    if (std::find(recipients.begin(), recipients.begin() + static_cast<std::ptrdiff_t>(i), r) !=
        recipients.begin() + static_cast<std::ptrdiff_t>(i)) {
      return make_error(Error::Code::invalid_argument, "team link: '" + message + "': recipient '" + r + "' listed twice");
    }
  }
  if (pending_.size() >= config_.max_unacknowledged) {
    return make_error(Error::Code::state, "team link: " + std::to_string(pending_.size()) +
                                              " notifications are still unacknowledged (limit " +
                                              std::to_string(config_.max_unacknowledged) + "); is a teammate down?");
  }
  const std::uint64_t seq = next_notify_seq_++;
  Pending p;
  p.seq = seq;
  p.message = message;
  p.waiting = recipients;
  if (now_us_) p.next_retransmit_us = *now_us_ + config_.retransmit_interval_us;
  transmit(p, out);
  ++stats_.sent;
  if (!p.waiting.empty()) pending_.push_back(std::move(p));
  return seq;
}

void TeamProtocol::transmit(const Pending& pending, std::vector<TeamDatagram>& out) {
  NotificationWire w;
  w.utime_us = utime();
  w.mission_id = config_.mission_id;
  w.session = session_;
  w.sender = config_.self;
  w.seq = pending.seq;
  w.message = pending.message;
  w.recipients = pending.waiting;
  auto bytes = encode_notification(w, key_);
  // Every field was checked by validate_team_link_config() and notify(), so
  // encoding cannot fail; if it ever did, the retransmission would try again.
  if (bytes) out.push_back({TeamChannel::notify, std::move(bytes.value())});
}

void TeamProtocol::tick(std::int64_t now_us, std::vector<TeamDatagram>& out) {
  note_time(now_us);
  for (auto& p : pending_) {
    if (!p.next_retransmit_us) {
      p.next_retransmit_us = now_us + config_.retransmit_interval_us;
    } else if (now_us >= *p.next_retransmit_us) {
      transmit(p, out);
      ++stats_.retransmissions;
      p.next_retransmit_us = now_us + config_.retransmit_interval_us;
    }
  }
}

void TeamProtocol::receive(std::int64_t now_us, TeamChannel channel, std::span<const std::uint8_t> bytes,
                           std::vector<TeamNotification>& delivered, std::vector<TeamDatagram>& out) {
  note_time(now_us);
  switch (channel) {
    case TeamChannel::notify: receive_notification(bytes, delivered, out); return;
    case TeamChannel::status: receive_status(bytes); return;
    case TeamChannel::telemetry: receive_telemetry(bytes); return;
    case TeamChannel::gate: receive_verdict(bytes); return;
  }
}

void TeamProtocol::receive_notification(std::span<const std::uint8_t> bytes, std::vector<TeamNotification>& delivered,
                                        std::vector<TeamDatagram>& out) {
  auto decoded = decode_notification(bytes, key_);
  if (!decoded) {
    ++stats_.malformed;
    return;
  }
  const NotificationWire& w = decoded->wire;
  // Multicast loops our own messages back to us; they are not news.
  if (w.sender == config_.self) return;
  if (w.mission_id != config_.mission_id) {
    ++stats_.rejected_other_mission;
    return;
  }
  if (!in_roster(w.sender)) {
    ++stats_.rejected_unknown_sender;
    return;
  }
  if (!decoded->tag_ok) {
    ++stats_.rejected_bad_tag;
    return;
  }
  if (!same_session(w.session)) return;
  if (now_us_) peers_[w.sender].last_heard_us = *now_us_;
  if (w.is_ack) {
    handle_ack(w);
    return;
  }
  if (!contains(w.recipients, config_.self)) return;
  switch (peers_[w.sender].notifications.accept(w.seq)) {
    case ReplayWindow::Verdict::fresh:
      ++stats_.accepted;
      delivered.push_back({w.sender, w.message, w.seq});
      send_ack(w, out);
      return;
    case ReplayWindow::Verdict::duplicate:
      // Delivered before: a retransmission whose ack was lost, or a replay.
      // Either way acknowledging again is harmless and stops the sender.
      ++stats_.rejected_replay;
      send_ack(w, out);
      return;
    case ReplayWindow::Verdict::too_old:
      // Cannot tell whether it was ever delivered, so it is neither delivered
      // nor acknowledged.
      ++stats_.rejected_replay;
      return;
  }
}

void TeamProtocol::handle_ack(const NotificationWire& ack) {
  if (ack.ack_sender != config_.self) return;
  ++stats_.acks_received;
  auto it = std::find_if(pending_.begin(), pending_.end(),
                         [&](const Pending& p) { return p.seq == ack.ack_seq && p.message == ack.message; });
  if (it == pending_.end()) return;
  auto& waiting = it->waiting;
  waiting.erase(std::remove(waiting.begin(), waiting.end(), ack.sender), waiting.end());
  if (waiting.empty()) pending_.erase(it);
}

void TeamProtocol::send_ack(const NotificationWire& notification, std::vector<TeamDatagram>& out) {
  NotificationWire ack;
  ack.utime_us = utime();
  ack.mission_id = config_.mission_id;
  ack.session = session_;
  ack.sender = config_.self;
  ack.message = notification.message;
  ack.is_ack = true;
  ack.ack_sender = notification.sender;
  ack.ack_seq = notification.seq;
  auto bytes = encode_notification(ack, key_);
  if (bytes) out.push_back({TeamChannel::notify, std::move(bytes.value())});
}

bool TeamProtocol::same_session(const std::string& session) {
  if (session == session_) return true;
  ++stats_.rejected_other_session;
  return false;
}

void TeamProtocol::set_session(const std::string& session) {
  if (session.empty() || is_lower_hex(session, kSessionHexDigits)) session_ = session;
}

std::optional<std::int64_t> TeamProtocol::last_heard_us(const std::string& robot) const {
  const auto it = peers_.find(robot);
  if (it == peers_.end()) return std::nullopt;
  return it->second.last_heard_us;
}

bool TeamProtocol::admit(const std::string& robot, const std::string& mission_id, const std::string* session,
                         bool tag_ok, std::uint64_t seq, std::optional<std::uint64_t> Peer::*last_seq) {
  if (robot == config_.self) return false;  // our own, looped back by multicast
  if (mission_id != config_.mission_id) {
    ++stats_.rejected_other_mission;
    return false;
  }
  if (!in_roster(robot)) {
    ++stats_.rejected_unknown_sender;
    return false;
  }
  if (!tag_ok) {
    ++stats_.rejected_bad_tag;
    return false;
  }
  if (session != nullptr) {
    if (!same_session(*session)) return false;
    if (now_us_) peers_[robot].last_heard_us = *now_us_;
  }
  auto& last = peers_[robot].*last_seq;
  // Only a newer message replaces the one we hold: an older one is stale
  // (reordered) or replayed.
  if (last && seq <= *last) {
    ++stats_.rejected_replay;
    return false;
  }
  last = seq;
  return true;
}

template <class Item>
void TeamProtocol::hold(std::vector<Item>& held, const std::string& robot, const Item& item) {
  auto same_robot = [&](const Item& h) { return h.robot == robot; };
  if (auto it = std::find_if(held.begin(), held.end(), same_robot); it != held.end()) {
    *it = item;
    return;
  }
  auto roster_index = [&](const std::string& name) {
    return std::find(config_.roster.begin(), config_.roster.end(), name) - config_.roster.begin();
  };
  auto pos = std::find_if(held.begin(), held.end(),
                          [&](const Item& h) { return roster_index(h.robot) > roster_index(robot); });
  held.insert(pos, item);
}

void TeamProtocol::receive_status(std::span<const std::uint8_t> bytes) {
  auto decoded = decode_status(bytes, key_);
  if (!decoded) {
    ++stats_.malformed;
    return;
  }
  const StatusWire& w = decoded->wire;
  if (!admit(w.status.robot, w.mission_id, &w.session, decoded->tag_ok, w.seq, &Peer::last_status_seq)) return;
  hold(teammate_status_, w.status.robot, w.status);
}

void TeamProtocol::receive_verdict(std::span<const std::uint8_t> bytes) {
  auto decoded = decode_verdict(bytes, key_);
  if (!decoded) {
    ++stats_.malformed;
    return;
  }
  const VerdictWire& w = decoded->wire;
  if (!admit(w.verdict.robot, w.mission_id, nullptr, decoded->tag_ok, w.seq, &Peer::last_verdict_seq)) return;
  ++stats_.verdicts_accepted;
  hold(teammate_verdicts_, w.verdict.robot, w.verdict);
}

void TeamProtocol::receive_telemetry(std::span<const std::uint8_t> bytes) {
  auto decoded = decode_telemetry(bytes, key_);
  if (!decoded) {
    ++stats_.malformed;
    return;
  }
  const TelemetryWire& w = decoded->wire;
  if (!admit(w.telemetry.robot, w.mission_id, &w.session, decoded->tag_ok, w.seq, &Peer::last_telemetry_seq)) return;
  ++stats_.telemetry_accepted;
  hold(teammate_telemetry_, w.telemetry.robot, w.telemetry);
}

Result<TeamDatagram> TeamProtocol::telemetry(const Telemetry& telemetry) {
  TelemetryWire w;
  w.utime_us = utime();
  w.mission_id = config_.mission_id;
  w.session = session_;
  w.seq = next_telemetry_seq_++;
  w.telemetry = telemetry;
  w.telemetry.robot = config_.self;
  w.telemetry.state = cut(telemetry.state);
  auto bytes = encode_telemetry(w, key_);
  if (!bytes) return bytes.error();
  return TeamDatagram{TeamChannel::telemetry, std::move(bytes.value())};
}

Result<TeamDatagram> TeamProtocol::status(const TeamStatus& status) {
  StatusWire w;
  w.utime_us = utime();
  w.mission_id = config_.mission_id;
  w.session = session_;
  w.seq = next_status_seq_++;
  w.status.robot = config_.self;
  w.status.phase = cut(status.phase);
  w.status.state = cut(status.state);
  w.status.reason = cut(status.reason);
  w.status.p_success = std::isfinite(status.p_success) ? status.p_success : -1.0;
  auto bytes = encode_status(w, key_);
  if (!bytes) return bytes.error();
  return TeamDatagram{TeamChannel::status, std::move(bytes.value())};
}

Result<TeamDatagram> TeamProtocol::verdict(const GateVerdict& verdict) {
  VerdictWire w;
  w.utime_us = utime();
  w.mission_id = config_.mission_id;
  w.seq = next_verdict_seq_++;
  w.verdict = verdict;
  w.verdict.robot = config_.self;
  w.verdict.detail = cut(verdict.detail);
  auto bytes = encode_verdict(w, key_);
  if (!bytes) return bytes.error();
  return TeamDatagram{TeamChannel::gate, std::move(bytes.value())};
}

bool TeamProtocol::acknowledged(std::uint64_t seq) const {
  if (seq < config_.first_seq || seq >= next_notify_seq_) return false;
  return std::none_of(pending_.begin(), pending_.end(), [seq](const Pending& p) { return p.seq == seq; });
}

}  // namespace p3at::hal
