#pragma once
/// The team link's protocol, without any transport: authentication, replay
/// rejection, acknowledgement and retransmission, teammates' status. Both
/// backends (LCM, hal/lcm; the simulated radio, sim_hal) run this same code
/// through DatagramTeamLink; it does no I/O and reads no clock, so it can be
/// unit-tested and fuzzed directly. Rules in docs/team-link.md.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/replay_window.hpp"
#include "p3at/hal/team_key.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/hal/team_wire.hpp"

namespace p3at::hal {

/// Who this robot is and who its teammates are.
struct TeamLinkConfig {
  std::string mission_id;            ///< messages of any other mission are dropped (counted)
  std::string self;                  ///< this robot's name; must be in `roster`
  std::vector<std::string> roster;   ///< every robot of the team, `self` included
  std::int64_t retransmit_interval_us = 200'000;  ///< between repeats of an unacknowledged notification
  std::size_t max_unacknowledged = 64;  ///< notify() refuses more outstanding notifications than this
  /// First sequence number of each of this robot's counters (notifications,
  /// status, telemetry), in [1, 2^62). Must be larger than any used by an
  /// earlier run of this robot in the same mission, or teammates take the new
  /// messages for replays: open_lcm_team_link() sets it to the wall-clock time
  /// in microseconds; the simulator uses a fixed value (one run per process).
  std::uint64_t first_seq = 1;
  std::int64_t utime_offset_us = 0;  ///< added to the caller's time to stamp `utime` (informational)
};

/// Ok, or invalid_argument naming the first bad field (empty or over-long
/// names, NUL bytes, duplicate roster names, `self` not in the roster,
/// non-positive interval or limit, first_seq out of range).
Status validate_team_link_config(const TeamLinkConfig& config);

/// The protocol state of one robot's end of the link. Not thread-safe.
/// Every outgoing message is appended to an `out` vector for the caller's
/// transport; incoming bytes are handed to receive().
class TeamProtocol {
 public:
  /// invalid_argument when validate_team_link_config() fails.
  static Result<TeamProtocol> create(TeamLinkConfig config, const TeamKey& key);

  /// Starts notification `message` for `recipients` (teammates, not self, no
  /// repeats; empty = broadcast that nobody acknowledges, acknowledged at once).
  /// Appends its first transmission to `out` and returns its sequence number.
  /// invalid_argument for a bad message name or recipient; Error::Code::state
  /// when max_unacknowledged notifications are still waiting for acks.
  Result<std::uint64_t> notify(const std::string& message, const std::vector<std::string>& recipients,
                               std::vector<TeamDatagram>& out);

  /// Handles one received datagram at time `now_us`: appends a newly accepted
  /// notification to `delivered` and acknowledgements to `out`; every rejection
  /// is counted in stats(). Any bytes are safe here.
  void receive(std::int64_t now_us, TeamChannel channel, std::span<const std::uint8_t> bytes,
               std::vector<TeamNotification>& delivered, std::vector<TeamDatagram>& out);

  /// Appends to `out` the retransmissions due at `now_us`: each unacknowledged
  /// notification is repeated every retransmit_interval_us, to the recipients
  /// that have not acknowledged it yet, until all have.
  void tick(std::int64_t now_us, std::vector<TeamDatagram>& out);

  /// This robot's telemetry / status as a datagram; `robot` is set to self and
  /// over-long text fields are cut to kMaxTeamTextBytes; a non-finite
  /// p_success is sent as -1 (unknown).
  Result<TeamDatagram> telemetry(const Telemetry& telemetry);
  Result<TeamDatagram> status(const TeamStatus& status);
  /// This robot's gate verdict as a datagram; `robot` is set to self and an
  /// over-long detail is cut. invalid_argument for a mission_hash that is not
  /// 64 lowercase hex digits or a non-finite number.
  Result<TeamDatagram> verdict(const GateVerdict& verdict);

  /// True once every recipient of our notification `seq` has acknowledged it
  /// (false for a sequence number this robot never issued).
  bool acknowledged(std::uint64_t seq) const;

  /// Latest authenticated status of each teammate heard from, in roster order.
  const std::vector<TeamStatus>& teammate_status() const { return teammate_status_; }
  /// Latest authenticated gate verdict / telemetry of each teammate heard from, in roster order.
  const std::vector<GateVerdict>& teammate_verdicts() const { return teammate_verdicts_; }
  const std::vector<Telemetry>& teammate_telemetry() const { return teammate_telemetry_; }
  const TeamLinkStats& stats() const { return stats_; }
  const TeamLinkConfig& config() const { return config_; }
  /// Notifications still waiting for acknowledgements.
  std::size_t unacknowledged() const { return pending_.size(); }

  /// The launch session (docs/launch-gate.md): "" or 64 lowercase hex digits
  /// (anything else is ignored). Sent in every notification, status and
  /// telemetry; received ones of another session are counted in
  /// rejected_other_session and dropped.
  void set_session(const std::string& session);
  const std::string& session() const { return session_; }
  /// When an authenticated message of this session last arrived from `robot`.
  std::optional<std::int64_t> last_heard_us(const std::string& robot) const;

 private:
  struct Pending {
    std::uint64_t seq = 0;
    std::string message;
    std::vector<std::string> waiting;  ///< recipients that have not acknowledged yet
    std::optional<std::int64_t> next_retransmit_us;
  };
  struct Peer {
    ReplayWindow notifications;
    std::optional<std::uint64_t> last_status_seq;
    std::optional<std::uint64_t> last_verdict_seq;
    std::optional<std::uint64_t> last_telemetry_seq;
    std::optional<std::int64_t> last_heard_us;
  };

  TeamProtocol(TeamLinkConfig config, const TeamKey& key);

  void note_time(std::int64_t now_us);
  std::int64_t utime() const;
  bool in_roster(const std::string& name) const;
  void receive_notification(std::span<const std::uint8_t> bytes, std::vector<TeamNotification>& delivered,
                            std::vector<TeamDatagram>& out);
  void receive_status(std::span<const std::uint8_t> bytes);
  void receive_verdict(std::span<const std::uint8_t> bytes);
  void receive_telemetry(std::span<const std::uint8_t> bytes);
  /// The checks every best-effort message (status, verdict, telemetry) passes
  /// before it is kept: not our own, our mission, a roster name, a good tag,
  /// our session (`session` null: not checked, for verdicts), a sequence number newer than the last one kept from that robot (which it
  /// then records). Each failure is counted; true when the message is kept.
  bool admit(const std::string& robot, const std::string& mission_id, const std::string* session, bool tag_ok,
             std::uint64_t seq, std::optional<std::uint64_t> Peer::*last_seq);
  /// True when `session` is ours; else counts rejected_other_session.
  bool same_session(const std::string& session);
  /// Replaces `robot`'s entry in `held` or inserts it in roster order.
  template <class Item>
  void hold(std::vector<Item>& held, const std::string& robot, const Item& item);
  void handle_ack(const NotificationWire& ack);
  void send_ack(const NotificationWire& notification, std::vector<TeamDatagram>& out);
  void transmit(const Pending& pending, std::vector<TeamDatagram>& out);

  TeamLinkConfig config_;
  TeamKey key_;
  std::uint64_t next_notify_seq_;
  std::uint64_t next_status_seq_;
  std::uint64_t next_telemetry_seq_;
  std::uint64_t next_verdict_seq_;
  std::optional<std::int64_t> now_us_;  ///< latest time seen; none before the first receive()/tick()
  std::string session_;
  std::vector<Pending> pending_;        ///< in sequence order
  std::map<std::string, Peer> peers_;
  std::vector<TeamStatus> teammate_status_;
  std::vector<GateVerdict> teammate_verdicts_;
  std::vector<Telemetry> teammate_telemetry_;
  TeamLinkStats stats_;
};

}  // namespace p3at::hal
