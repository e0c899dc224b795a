#pragma once
/// The robots' team link: authenticated notifications (the FSA's Notify /
/// Notified / MessageSent), telemetry and mission status. Backends: LCM over UDP
/// multicast (hal/lcm, real robots and hardware-in-the-loop tests) and the
/// simulated radio (sim_hal, fast time).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
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

/// A launch-gate decision as published on the team link (docs/launch-gate.md).
enum class GateDecision {
  go,           ///< the verifier's probability meets the threshold and every criterion holds
  no_go,        ///< it does not: no robot of the team may move
  override_go,  ///< the operator overrode this robot's decision with --override-gate
};
/// "GO", "NO-GO", "OVERRIDE" (the wire spelling).
constexpr const char* to_string(GateDecision decision) {
  switch (decision) {
    case GateDecision::go: return "GO";
    case GateDecision::no_go: return "NO-GO";
    case GateDecision::override_go: return "OVERRIDE";
  }
  return "?";
}
/// Inverse of to_string(GateDecision); nullopt for anything else (case-sensitive).
constexpr std::optional<GateDecision> gate_decision_from_string(std::string_view text) {
  for (const GateDecision d : {GateDecision::go, GateDecision::no_go, GateDecision::override_go}) {
    if (text == to_string(d)) return d;
  }
  return std::nullopt;
}
/// True for the decisions that let the team launch (GO and OVERRIDE).
constexpr bool allows_launch(GateDecision decision) { return decision != GateDecision::no_go; }

/// A teammate's gate nonce, as heard by the robot that publishes a verdict.
struct HeardNonce {
  std::string robot;
  std::string nonce;
  bool operator==(const HeardNonce&) const = default;
};

/// One robot's launch-gate verdict (authenticated like everything else).
/// The last three fields make the launch an agreement of this very run
/// (docs/launch-gate.md): `nonce` is fresh for every gate, `heard` echoes the
/// teammates' nonces the sender has heard, `session` is set once the sender
/// has committed to launching with exactly those teammates.
struct GateVerdict {
  std::string robot;         ///< the sender (set by the link when publishing)
  std::string mission_hash;  ///< 64 lowercase hex digits: what the verdict is about
  GateDecision decision = GateDecision::no_go;
  double p_time = -1.0;      ///< P(done by tmax_s); < 0 when unknown
  double p_radius = -1.0;    ///< P(every robot within rmax_m of its goal); < 0 when unknown
  double p_joint = -1.0;     ///< P(both); < 0 when unknown
  double threshold = 0.0;    ///< the launch threshold applied
  double tmax_s = 0.0;       ///< the criteria applied
  double rmax_m = 0.0;
  std::string detail;        ///< failed criteria, or why overridden
  std::string nonce;         ///< 32 lowercase hex digits, random, one per gate (empty only in tests of old code paths)
  std::string session;       ///< "" until committed; then the session id (64 lowercase hex digits)
  std::vector<HeardNonce> heard;  ///< teammates' nonces the sender has heard, at most one per teammate
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

  /// Publishes this robot's launch-gate verdict (best effort, not
  /// acknowledged: the gate republishes it until the team has agreed).
  virtual Status publish_verdict(const GateVerdict& verdict) = 0;
  /// The latest authenticated gate verdict of each teammate that has sent one.
  virtual const std::vector<GateVerdict>& teammate_verdicts() const = 0;
  /// The latest authenticated telemetry of each teammate that has sent some
  /// (in-mission re-verification reads where the team is).
  virtual const std::vector<Telemetry>& teammate_telemetry() const = 0;

  virtual const TeamLinkStats& stats() const = 0;

  /// The launch session this robot belongs to ("" before the gate has
  /// committed). Every notification, status and telemetry sent carries it;
  /// those received with any other session are dropped and counted in
  /// rejected_other_session. Verdicts are exempt: they establish the session.
  virtual void set_session(const std::string& session) = 0;
  virtual const std::string& session() const = 0;

  /// When (in the time passed to poll()) an authenticated message of this
  /// session last arrived from `robot`; nullopt if none has yet.
  virtual std::optional<std::int64_t> last_heard_us(const std::string& robot) const = 0;
};

}  // namespace p3at::hal
