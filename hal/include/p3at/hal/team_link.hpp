#pragma once
/// The robots' team link as the executive uses it: authenticated
/// notifications (the FSA's Notify / Notified / MessageSent), telemetry and
/// mission status. The protocol is p3at_team_link's (team_link/); its
/// transports are LCM over UDP multicast (hal/lcm, real robots and
/// hardware-in-the-loop tests) and the simulated radio (sim_hal, fast time).
/// The launch gate's verdicts travel on the same link, through the wider
/// interface gate::VerdictLink (launch_gate/verdict), which the executive
/// never sees.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"

namespace p3at::hal {

/// A notification received from a teammate, after authentication.
struct TeamNotification {
  std::string sender;    ///< robot name
  std::string message;   ///< the mission's message name
  std::uint64_t seq = 0; ///< sender's sequence number
};

/// A teammate's mission status (also authenticated).
struct TeamStatus {
  std::string robot;
  std::string phase;   ///< "gate", "running", "finished", "aborted"
  std::string state;   ///< current FSA state
  std::string reason;  ///< why aborted / what the gate decided
  double p_success = -1.0;  ///< latest verified probability, < 0 when unknown
};

/// Telemetry a robot publishes every cycle or few.
struct Telemetry {
  std::string robot;
  std::string state;
  double x_m = 0, y_m = 0, theta_rad = 0;  ///< odometry in the mission frame
  double trans_vel_mps = 0, rot_vel_radps = 0;
  std::uint64_t cycles = 0, overruns = 0, missed_updates = 0;
  double cycle_p50_us = 0, cycle_p99_us = 0;
};

/// Counters of what the link accepted and rejected; never reset.
struct TeamLinkStats {
  std::uint64_t sent = 0;             ///< notifications sent (first transmissions)
  std::uint64_t retransmissions = 0;  ///< repeats of unacknowledged notifications
  std::uint64_t accepted = 0;         ///< authenticated, new notifications delivered
  std::uint64_t acks_received = 0;
  std::uint64_t rejected_unknown_sender = 0;
  std::uint64_t rejected_bad_tag = 0;
  std::uint64_t rejected_replay = 0;  ///< sequence number not newer than the last accepted
  std::uint64_t rejected_other_mission = 0;
  std::uint64_t rejected_other_session = 0;  ///< authenticated, but from another launch session (a replay of another run)
  std::uint64_t malformed = 0;        ///< could not be decoded at all
  std::uint64_t verdicts_accepted = 0;   ///< authenticated, newer gate verdicts from teammates
  std::uint64_t telemetry_accepted = 0;  ///< authenticated, newer telemetry from teammates
};

/// One robot's end of the team link. Non-blocking: every call returns at once.
class TeamLink {
 public:
  TeamLink() = default;
  TeamLink(const TeamLink&) = delete;
  TeamLink& operator=(const TeamLink&) = delete;
  virtual ~TeamLink() = default;

  /// Broadcasts that `message` is now true, to be acknowledged by each of
  /// `recipients`; retransmitted by poll() until all have acknowledged.
  /// Returns the notification's sequence number.
  virtual Result<std::uint64_t> notify(const std::string& message, const std::vector<std::string>& recipients) = 0;

  /// True once every recipient of notification `seq` has acknowledged it.
  virtual bool acknowledged(std::uint64_t seq) const = 0;

  /// Handles incoming traffic and retransmissions at time `now_us`; appends
  /// newly accepted notifications to `received` (never a rejected one).
  virtual Status poll(std::int64_t now_us, std::vector<TeamNotification>& received) = 0;

  /// Publishes this robot's telemetry / status (best effort, not acknowledged).
  virtual Status publish_telemetry(const Telemetry& telemetry) = 0;
  virtual Status publish_status(const TeamStatus& status) = 0;

  /// The latest authenticated status of each teammate that has sent one.
  virtual const std::vector<TeamStatus>& teammate_status() const = 0;

  /// The latest authenticated telemetry of each teammate that has sent some
  /// (in-mission re-verification reads where the team is).
  virtual const std::vector<Telemetry>& teammate_telemetry() const = 0;

  virtual const TeamLinkStats& stats() const = 0;

  /// The launch session this robot belongs to ("" before the gate has
  /// committed). Every notification, status and telemetry sent carries it;
  /// those received with any other session are dropped and counted in
  /// rejected_other_session. Verdicts (gate::VerdictLink) are exempt: they establish
  /// the session.
  virtual void set_session(const std::string& session) = 0;
  virtual const std::string& session() const = 0;

  /// When (in the time passed to poll()) an authenticated message of this
  /// session last arrived from `robot`; nullopt if none has yet.
  virtual std::optional<std::int64_t> last_heard_us(const std::string& robot) const = 0;
};

}  // namespace p3at::hal
