#pragma once
/// The client of a Pioneer's firmware (ARCOS), over any byte stream: the
/// SYNC handshake, OPEN, CONFIG, ENABLE, keep-alive, SIPs into robot state,
/// link-loss detection, reconnect and clean disconnect. It follows the
/// protocol reference (docs/arcos-protocol.md), not any one simulator, so it
/// works with a real P3-AT on serial, with MobileSim-compatible simulators and
/// with our p3at_sim on TCP.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"
#include "p3at/bridge/odometry_tracker.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"

namespace p3at::bridge {

/// Timing and behaviour of a session. Defaults are the real protocol's.
struct ClientConfig {
  int sync_step_timeout_ms = 1000;   ///< wait for each SYNC echo (ARIA: 1000 ms)
  int handshake_timeout_ms = 6000;   ///< give up connecting after this (ARIA: ~6 s)
  int config_retry_ms = 200;         ///< CONFIG repeated this often…
  int config_timeout_ms = 1000;      ///< …for at most this long; no answer is tolerated
  int keepalive_ms = 500;            ///< the longest silence towards the robot…
  int keepalive_sips = 5;            ///< …or this many SIPs, whichever comes first: a simulator
                                     ///< running faster than real time sends SIPs faster, and its
                                     ///< watchdog counts simulated time
  /// The keep-alive repeats the motion in force only while the caller keeps
  /// asking for it: after this many SIPs without a set_velocity() call (the
  /// caller stalled: stopped, starved, or reading a backlog of stale SIPs) it
  /// sends STOP instead, once. 0 = never (the default: an operator's tool sets
  /// a velocity once and expects it kept); mission_exec, whose executive asks
  /// every cycle, uses 10 SIPs, half the firmware watchdog (2 s).
  int motion_stale_sips = 0;
  int link_loss_ms = 1000;           ///< no SIP for this long → link lost
  /// OPEN and ENABLE are single packets that a lossy line, a stalled peer or a
  /// busy simulator can lose; without them a robot never streams SIPs or never
  /// moves. Both are resent on a bounded schedule (docs/hal.md, "Handshake
  /// resends"): OPEN when no SIP follows it within open_resend_ms (3 SIP cycles
  /// of 100 ms: the first SIP is due within one)…
  int open_resend_ms = 300;
  int open_attempts = 5;             ///< …at most this many OPENs in all (1.5 s), then give up
  /// ENABLE 1 again when this many SIPs after it still show the motors off (a
  /// SIP already in flight when ENABLE arrives may predate it: one is normal)…
  /// The same bounds confirm enable_motors(true) and enable_motors(false)
  /// (ENABLE 0: resent while the SIPs still show the motors on) after connecting.
  int enable_resend_sips = 3;
  int enable_attempts = 5;           ///< …at most this many ENABLEs in all (15 SIPs, 1.5 s), then give up
  int close_grace_ms = 100;          ///< between ENABLE 0 and CLOSE on disconnect
  bool serial_preamble = false;      ///< send ARIA's "WMS2\r" first (serial links only)
  bool enable_motors = true;         ///< ENABLE 1 after connecting
  bool auto_reconnect = true;        ///< wait_for_update retries a lost link…
  int reconnect_interval_ms = 1000;  ///< …at most this often
  std::string log_name = "bridge";   ///< component name in log lines
};

/// What the robot told us about itself while connecting.
struct RobotInfo {
  arcos::RobotIdentity identity;
  std::optional<arcos::ConfigPacket> config;  ///< absent when CONFIG went unanswered
  arcos::RobotParams params;                  ///< conversion factors for the subclass
};

/// Counters a person or a test can read; never reset.
struct ClientStats {
  std::uint64_t sips = 0;
  std::uint64_t other_packets = 0;    ///< valid non-SIP packets after the handshake
  std::uint64_t bad_sips = 0;         ///< SIP packets that failed to decode
  std::uint64_t commands_sent = 0;
  std::uint64_t keepalives_sent = 0;  ///< PULSEs or VEL/RVEL repeats sent only to keep the link alive
  std::uint64_t stale_motion_stops = 0;  ///< STOPs sent because the caller stopped asking for motion
  std::uint64_t handshakes = 0;       ///< completed handshakes
  std::uint64_t handshake_failures = 0;
  std::uint64_t open_resends = 0;     ///< OPENs sent again because no SIP followed
  std::uint64_t enable_resends = 0;   ///< ENABLE 1s sent again because SIPs showed the motors off
  std::uint64_t disable_resends = 0;  ///< ENABLE 0s sent again because SIPs showed the motors on
  /// enable_motors() calls that gave up with the motors not as asked (a give-up
  /// while connecting counts in handshake_failures instead)
  std::uint64_t motor_switch_failures = 0;
  std::uint64_t link_losses = 0;
  std::uint64_t reconnects = 0;       ///< completed handshakes after a link loss
  std::uint64_t refused_motion = 0;   ///< motion requests refused because the link was not ok
};

/// Opens a fresh byte stream to the robot; called on connect and reconnect.
using StreamOpener = std::function<Result<std::unique_ptr<hal::ByteStream>>()>;

/// A Pioneer drive base reached over ARCOS. Single-threaded: one owner calls it.
class ArcosClient final : public hal::DriveBase {
 public:
  ArcosClient(StreamOpener opener, hal::Clock& clock, ClientConfig config = {});
  ~ArcosClient() override;

  /// Opens the stream and runs the handshake: SYNC0/1/2 (with retries and the
  /// "robot still open" recovery), OPEN, CONFIG, ENABLE. Blocks at most
  /// handshake_timeout_ms plus the CONFIG wait. On success link == ok.
  Status connect();

  /// ENABLE 0, a short grace, CLOSE, then closes the stream. Safe to call twice.
  Status disconnect();

  // hal::DriveBase
  Status set_velocity(double trans_mps, double rot_radps) override;
  Status stop() override;
  Status emergency_stop() override;
  Result<bool> wait_for_update(int timeout_ms) override;
  const hal::DriveState& state() const override { return state_; }

  /// HEAD: turn to an absolute heading in the firmware's frame (degrees).
  Status set_heading(int heading_deg);
  /// MOVE: drive a relative distance (mm) under firmware control.
  Status move(int distance_mm);
  /// ENABLE 1 / 0, confirmed from the SIPs' motor flag (FLAGS bit 0) and resent
  /// like the connect-time ENABLE (docs/hal.md, "Handshake resends"): blocks
  /// until a SIP after the command shows the motors as asked (normally one or
  /// two SIP cycles), at most enable_attempts × enable_resend_sips SIPs (1.5 s).
  /// enable_motors(true) clears a latched emergency stop once confirmed; when
  /// it gives up (ENABLE lost, e-stop pressed) it returns the error and motion
  /// stays refused until an enable succeeds. enable_motors(false) refuses
  /// motion from the start; when the motors stay on it logs an ERROR, sends
  /// ESTOP as a last resort and returns the error.
  Status enable_motors(bool enable);

  const RobotInfo& info() const { return info_; }
  const ClientStats& stats() const { return stats_; }
  const arcos::DecoderStats& decoder_stats() const { return decoder_.stats(); }

 private:
  Status handshake();
  Status sync_once();
  /// OPEN, resent until the first SIP arrives (at most open_attempts OPENs).
  Status open_until_sips();
  /// ENABLE `on`, resent until a SIP after it shows the motors on (resp. off),
  /// at most enable_attempts; used while connecting and by enable_motors().
  Status switch_motors_until_confirmed(bool on);
  /// Why motion is refused although the link is ok; empty when it is not.
  std::string motion_latch_reason() const;
  /// The error a refused motion request returns: the link state and any latch.
  Status motion_refused() const;
  /// Next packet with `id` (any packet when nullopt), handling SIPs on the way when sips_ok.
  Result<arcos::Packet> wait_for_packet(std::optional<std::uint8_t> id, std::int64_t deadline_us, bool sips_ok);
  Status read_and_dispatch(int timeout_ms);
  void handle_packet(const arcos::Packet& packet);
  void handle_sip(const arcos::Packet& packet);
  Status send(const arcos::Frame& frame);
  Status send_motion();
  void service_keepalive();
  /// What came back since the handshake started (`before`: the decoder's counters then).
  std::string handshake_diagnosis(const arcos::DecoderStats& before) const;
  void check_link();
  void lose_link(const std::string& why);
  bool motion_allowed(const char* what);
  int ms_until_keepalive() const;

  StreamOpener opener_;
  hal::Clock& clock_;
  ClientConfig config_;
  std::unique_ptr<hal::ByteStream> stream_;
  arcos::PacketDecoder decoder_;
  OdometryTracker odometry_;
  hal::DriveState state_;
  RobotInfo info_;
  ClientStats stats_;
  std::vector<arcos::Packet> inbox_;  // non-SIP packets waiting for the handshake
  std::int64_t last_sip_us_ = 0;
  std::int64_t last_sent_us_ = 0;
  std::uint64_t sips_at_last_send_ = 0;
  std::uint64_t sips_at_motion_request_ = 0;  ///< stats_.sips at the latest set_velocity()
  std::uint64_t handshake_bytes_ = 0;  ///< bytes read during the current handshake
  std::int64_t last_reconnect_attempt_us_ = 0;
  bool estop_latched_ = false;
  /// Set by enable_motors(false) and by a failed enable_motors(true): the
  /// motors are (or may be) off, so motion is refused, saying this, until an
  /// enable is confirmed. Empty = no such latch.
  std::string motors_off_why_;
  bool ever_connected_ = false;
  bool opened_ = false;               // OPEN sent on the current stream
  bool motion_active_ = false;        // a non-zero VEL/RVEL is in force
  int vel_mm_s_ = 0;
  int rvel_deg_s_ = 0;
};

}  // namespace p3at::bridge
