#include "p3at/team_link/datagram_team_link.hpp"

namespace p3at::hal {

void DatagramTeamLink::send_all(std::vector<TeamDatagram>& datagrams) {
  for (const auto& d : datagrams) {
    auto s = transmit(d, now_us_);
    if (!s && !deferred_) deferred_ = s.error();
  }
  datagrams.clear();
}

Result<std::uint64_t> DatagramTeamLink::notify(const std::string& message, const std::vector<std::string>& recipients) {
  auto seq = protocol_.notify(message, recipients, outbox_);
  send_all(outbox_);
  return seq;
}

Status DatagramTeamLink::poll(std::int64_t now_us, std::vector<TeamNotification>& received) {
  if (now_us > now_us_) now_us_ = now_us;
  inbox_.clear();
  if (auto s = collect(now_us, inbox_); !s && !deferred_) deferred_ = s.error();
  for (const auto& d : inbox_) {
    protocol_.receive(now_us, d.channel, d.bytes, received, outbox_);
    // Acks go out as soon as they are due, before the next datagram is read.
    send_all(outbox_);
  }
  protocol_.tick(now_us, outbox_);
  send_all(outbox_);
  if (deferred_) {
    Error e = std::move(*deferred_);
    deferred_.reset();
    return e;
  }
  return {};
}

Status DatagramTeamLink::publish_telemetry(const Telemetry& telemetry) {
  auto datagram = protocol_.telemetry(telemetry);
  if (!datagram) return datagram.error();
  return transmit(datagram.value(), now_us_);
}

Status DatagramTeamLink::publish_status(const TeamStatus& status) {
  auto datagram = protocol_.status(status);
  if (!datagram) return datagram.error();
  return transmit(datagram.value(), now_us_);
}

Status DatagramTeamLink::publish_verdict(const gate::GateVerdict& verdict) {
  auto datagram = protocol_.verdict(verdict);
  if (!datagram) return datagram.error();
  return transmit(datagram.value(), now_us_);
}

}  // namespace p3at::hal
