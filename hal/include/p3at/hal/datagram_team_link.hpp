#pragma once
/// A TeamLink over any datagram transport. The whole protocol lives in
/// TeamProtocol; a backend only moves datagrams: LcmTeamLink (hal/lcm, real
/// UDP multicast) and sim::SimTeamLink (the simulated radio).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/hal/team_link.hpp"
#include "p3at/hal/team_protocol.hpp"
#include "p3at/hal/team_wire.hpp"

namespace p3at::hal {

class DatagramTeamLink : public TeamLink {
 public:
  explicit DatagramTeamLink(TeamProtocol protocol) : protocol_(std::move(protocol)) {}

  /// Sends the first transmission at once (stamped with the time of the latest
  /// poll()). If the transport fails, the notification stays queued and is
  /// retransmitted; the failure is reported by the next poll().
  Result<std::uint64_t> notify(const std::string& message, const std::vector<std::string>& recipients) final;
  bool acknowledged(std::uint64_t seq) const final { return protocol_.acknowledged(seq); }
  /// Receives everything that has arrived, then sends acks and due
  /// retransmissions. Returns the first transport error since the last poll
  /// (after doing all of that work), if any.
  Status poll(std::int64_t now_us, std::vector<TeamNotification>& received) final;
  Status publish_telemetry(const Telemetry& telemetry) final;
  Status publish_status(const TeamStatus& status) final;
  const std::vector<TeamStatus>& teammate_status() const final { return protocol_.teammate_status(); }
  Status publish_verdict(const GateVerdict& verdict) final;
  const std::vector<GateVerdict>& teammate_verdicts() const final { return protocol_.teammate_verdicts(); }
  const std::vector<Telemetry>& teammate_telemetry() const final { return protocol_.teammate_telemetry(); }
  const TeamLinkStats& stats() const final { return protocol_.stats(); }
  void set_session(const std::string& session) final { protocol_.set_session(session); }
  const std::string& session() const final { return protocol_.session(); }
  std::optional<std::int64_t> last_heard_us(const std::string& robot) const final {
    return protocol_.last_heard_us(robot);
  }

  const TeamProtocol& protocol() const { return protocol_; }

 protected:
  /// Sends one datagram, best effort, stamped `now_us` (the simulated radio
  /// uses it as the send time).
  virtual Status transmit(const TeamDatagram& datagram, std::int64_t now_us) = 0;
  /// Appends every datagram that has arrived by `now_us`, in arrival order.
  virtual Status collect(std::int64_t now_us, std::vector<TeamDatagram>& arrived) = 0;

 private:
  void send_all(std::vector<TeamDatagram>& datagrams);

  TeamProtocol protocol_;
  std::int64_t now_us_ = 0;           ///< time of the latest poll()
  std::optional<Error> deferred_;     ///< first transport error not yet reported
  std::vector<TeamDatagram> inbox_;   ///< reused buffers
  std::vector<TeamDatagram> outbox_;
};

}  // namespace p3at::hal
