#include "p3at/bridge/arcos_client.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "p3at/common/log.hpp"
#include "p3at/protocols/arcos/commands.hpp"

namespace p3at::bridge {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool is_sip(std::uint8_t id) { return id == arcos::kSipStopped || id == arcos::kSipMoving; }

int round_to_int(double value) { return static_cast<int>(std::lround(value)); }

int ms_between(std::int64_t from_us, std::int64_t to_us) {
  const std::int64_t ms = (to_us - from_us + 999) / 1000;
  return static_cast<int>(std::clamp<std::int64_t>(ms, 0, 60'000));
}

}  // namespace

ArcosClient::ArcosClient(StreamOpener opener, hal::Clock& clock, ClientConfig config)
    : opener_(std::move(opener)), clock_(clock), config_(std::move(config)), odometry_(arcos::RobotParams{}) {
  state_.sonar_m.fill(-1.0);
  inbox_.reserve(8);
}

ArcosClient::~ArcosClient() {
  if (stream_) (void)disconnect();
}

Status ArcosClient::connect() {
  if (stream_) {
    stream_->close();
    stream_.reset();
  }
  const bool was_lost = state_.link == hal::LinkState::link_lost;
  state_.link = hal::LinkState::connecting;
  opened_ = false;
  motion_active_ = false;
  vel_mm_s_ = 0;
  rvel_deg_s_ = 0;
  auto opened = opener_();
  if (!opened) {
    state_.link = was_lost ? hal::LinkState::link_lost : hal::LinkState::disconnected;
    state_.why_stopped = opened.error().message;
    return opened.error();
  }
  stream_ = std::move(opened).value();
  decoder_ = arcos::PacketDecoder{};
  inbox_.clear();
  const Status result = handshake();
  if (!result) {
    ++stats_.handshake_failures;
    log::warn(config_.log_name, "event=handshake-failed url=" + stream_->describe() + " why=\"" +
                                    result.error().message + "\"");
    stream_->close();
    stream_.reset();
    opened_ = false;
    state_.link = was_lost ? hal::LinkState::link_lost : hal::LinkState::disconnected;
    state_.why_stopped = result.error().message;
    return result;
  }
  ++stats_.handshakes;
  if (was_lost) ++stats_.reconnects;
  ever_connected_ = true;
  log::info(config_.log_name, "event=connected url=" + stream_->describe() + " name=" + info_.identity.name +
                                  " class=" + info_.identity.robot_class + " subclass=" + info_.identity.subclass +
                                  " config=" + (info_.config ? "yes" : "none"));
  return {};
}

Status ArcosClient::handshake() {
  const std::int64_t deadline = clock_.now_us() + std::int64_t{config_.handshake_timeout_ms} * 1000;
  if (config_.serial_preamble) {
    // ARIA wakes a serial controller with this text, then ignores what comes back for 200 ms.
    static constexpr std::array<std::uint8_t, 5> kPreamble{'W', 'M', 'S', '2', '\r'};
    if (auto st = stream_->write_all(kPreamble); !st) return st;
    const std::int64_t quiet_until = clock_.now_us() + 200'000;
    std::array<std::uint8_t, 256> scratch{};
    while (clock_.now_us() < quiet_until) {
      auto got = stream_->read_some(scratch, ms_between(clock_.now_us(), quiet_until));
      if (!got) return got.error();
    }
  }

  // What came back during the handshake says why it failed: nothing, garbage
  // (a wrong device or baud rate), or packets with bad checksums (noise).
  const arcos::DecoderStats decoder_at_start = decoder_.stats();
  handshake_bytes_ = 0;
  Status synced = make_error(Error::Code::timeout, stream_->describe() + ": no robot responding (SYNC0 unanswered)");
  while (clock_.now_us() < deadline) {
    synced = sync_once();
    if (synced) break;
    if (synced.error().code == Error::Code::closed || synced.error().code == Error::Code::io) return synced;
    log::debug(config_.log_name, "event=sync-retry why=\"" + synced.error().message + "\"");
  }
  if (!synced) {
    return make_error(Error::Code::timeout, stream_->describe() + ": could not connect, no robot responding (" +
                                                synced.error().message + "; " + handshake_diagnosis(decoder_at_start) +
                                                ")");
  }

  info_.params = arcos::RobotParams::for_subclass(info_.identity.subclass);
  odometry_ = OdometryTracker(info_.params);
  if (auto st = open_until_sips(); !st) return st;

  // CONFIG is optional: repeat it for a while, and carry on without it.
  info_.config.reset();
  const std::int64_t config_deadline = clock_.now_us() + std::int64_t{config_.config_timeout_ms} * 1000;
  std::int64_t next_request = clock_.now_us();
  while (clock_.now_us() < config_deadline && !info_.config) {
    if (clock_.now_us() >= next_request) {
      if (auto st = send(arcos::encode_command(arcos::Command::config, 1)); !st) return st;
      next_request += std::int64_t{config_.config_retry_ms} * 1000;
    }
    auto packet = wait_for_packet(arcos::kConfigPacket, std::min(next_request, config_deadline), true);
    if (packet) {
      info_.config = arcos::decode_config(packet.value());
    } else if (packet.error().code != Error::Code::timeout) {
      return packet.error();
    }
  }
  if (info_.config && (info_.config->rot_vel_max == 0 || info_.config->trans_vel_max == 0)) {
    log::warn(config_.log_name, "event=config-zero-velocity-max why=\"robot reports a zero velocity maximum; "
                                "it may refuse to move\"");
  }

  if (config_.enable_motors) {
    if (auto st = switch_motors_until_confirmed(true); !st) return st;
    estop_latched_ = false;
    motors_off_why_.clear();
  }
  state_.link = hal::LinkState::ok;
  state_.why_stopped.clear();
  return {};
}

Status ArcosClient::open_until_sips() {
  const std::uint64_t sips_before = stats_.sips;
  for (int attempt = 1; attempt <= config_.open_attempts; ++attempt) {
    if (attempt > 1) {
      ++stats_.open_resends;
      log::warn(config_.log_name, "event=open-resend attempt=" + std::to_string(attempt) + "/" +
                                      std::to_string(config_.open_attempts) + " why=\"no SIP within " +
                                      std::to_string(config_.open_resend_ms) + " ms of OPEN\"");
    }
    if (auto st = send(arcos::encode_command(arcos::Command::open, 1)); !st) return st;
    opened_ = true;
    const std::int64_t resend_at = clock_.now_us() + std::int64_t{config_.open_resend_ms} * 1000;
    while (stats_.sips == sips_before && clock_.now_us() < resend_at) {
      if (auto st = read_and_dispatch(ms_between(clock_.now_us(), resend_at)); !st) return st;
    }
    if (stats_.sips != sips_before) return {};
  }
  return make_error(Error::Code::timeout,
                    stream_->describe() + ": robot opened but sent no SIP (" + std::to_string(config_.open_attempts) +
                        " OPENs, " + std::to_string(config_.open_resend_ms) + " ms apart: OPEN or the SIPs lost)");
}

Status ArcosClient::switch_motors_until_confirmed(bool on) {
  const std::int64_t sip_period_limit_us = std::int64_t{config_.link_loss_ms} * 1000;
  const std::string command = on ? "ENABLE" : "ENABLE 0";
  for (int attempt = 1; attempt <= config_.enable_attempts; ++attempt) {
    if (attempt > 1) {
      ++(on ? stats_.enable_resends : stats_.disable_resends);
      log::warn(config_.log_name, std::string("event=") + (on ? "enable" : "disable") + "-resend attempt=" +
                                      std::to_string(attempt) + "/" + std::to_string(config_.enable_attempts) +
                                      " why=\"" + std::to_string(config_.enable_resend_sips) + " SIPs after " +
                                      command + " show the motors " + (on ? "off" : "on") + "\"");
    }
    if (auto st = send(arcos::encode_command(arcos::Command::enable, on ? 1 : 0)); !st) return st;
    // Judge by SIPs that arrive after the command, never by an earlier one.
    const std::uint64_t sips_at_send = stats_.sips;
    std::int64_t sip_deadline = clock_.now_us() + sip_period_limit_us;
    while (stats_.sips - sips_at_send < static_cast<std::uint64_t>(config_.enable_resend_sips)) {
      const std::uint64_t before = stats_.sips;
      if (auto st = read_and_dispatch(ms_between(clock_.now_us(), sip_deadline)); !st) return st;
      if (stats_.sips != before) {
        if (state_.motors_enabled == on) return {};
        sip_deadline = clock_.now_us() + sip_period_limit_us;
      } else if (clock_.now_us() >= sip_deadline) {
        return make_error(Error::Code::timeout, stream_->describe() + ": SIPs stopped while " +
                                                    (on ? "enabling" : "disabling") + " the motors");
      }
    }
  }
  const std::string tries = std::to_string(config_.enable_attempts) + " " + command + " commands, " +
                            std::to_string(config_.enable_resend_sips) + " SIPs apart";
  if (!on) {
    return make_error(Error::Code::protocol,
                      stream_->describe() + ": motors stayed ON after " + tries + " (DISABLE lost? the robot can drive)");
  }
  return make_error(Error::Code::protocol,
                    stream_->describe() + ": motors stayed off after " + tries +
                        (state_.estop_pressed ? " (the robot reports its e-stop pressed)" : " (ENABLE lost?)"));
}

Status ArcosClient::sync_once() {
  for (std::uint8_t step = arcos::kSync0; step <= arcos::kSync2; ++step) {
    if (auto st = send(arcos::encode_command(step)); !st) return st;
    const std::int64_t step_deadline = clock_.now_us() + std::int64_t{config_.sync_step_timeout_ms} * 1000;
    while (true) {
      // During SYNC every reply matters (a SIP means the robot is still open).
      auto packet = wait_for_packet(std::nullopt, step_deadline, false);
      if (!packet) {
        if (packet.error().code == Error::Code::timeout) {
          return make_error(Error::Code::timeout, "SYNC" + std::to_string(step) + " unanswered");
        }
        return packet.error();
      }
      const arcos::Packet& p = packet.value();
      if (is_sip(p.id)) {
        // The robot is still open from an earlier client: close it and start over.
        (void)send(arcos::encode_command(arcos::Command::close, 1));
        inbox_.clear();
        return make_error(Error::Code::protocol, "robot was still open; sent CLOSE");
      }
      if (p.id == arcos::kCloseReply) {
        inbox_.clear();
        return make_error(Error::Code::protocol, "robot asked for a restart (0xFF)");
      }
      if (p.id == step) {
        if (step == arcos::kSync2) info_.identity = arcos::decode_identity(p);
        break;
      }
      // A stale echo of an earlier step (we may have repeated a SYNC): ignore it.
    }
  }
  return {};
}

Result<arcos::Packet> ArcosClient::wait_for_packet(std::optional<std::uint8_t> id, std::int64_t deadline_us,
                                                   bool sips_ok) {
  while (true) {
    while (!inbox_.empty()) {
      arcos::Packet packet = inbox_.front();
      inbox_.erase(inbox_.begin());
      if (sips_ok && is_sip(packet.id)) {
        handle_sip(packet);
        continue;
      }
      if (!id || packet.id == *id) return packet;
      ++stats_.other_packets;
    }
    const std::int64_t now = clock_.now_us();
    if (now >= deadline_us) return make_error(Error::Code::timeout, "timed out");
    std::array<std::uint8_t, 512> buffer{};
    auto got = stream_->read_some(buffer, ms_between(now, deadline_us));
    if (!got) return got.error();
    if (got.value() == 0) {
      decoder_.expire(clock_.now_us());
      continue;
    }
    handshake_bytes_ += got.value();
    decoder_.feed(std::span<const std::uint8_t>(buffer.data(), got.value()), clock_.now_us(),
                  [this](const arcos::Packet& p) { inbox_.push_back(p); });
  }
}

std::string ArcosClient::handshake_diagnosis(const arcos::DecoderStats& before) const {
  const arcos::DecoderStats& now = decoder_.stats();
  if (handshake_bytes_ == 0) return "nothing came back";
  const std::uint64_t packets = now.packets - before.packets;
  const std::uint64_t bad_checksum = now.bad_checksum - before.bad_checksum;
  const std::uint64_t garbage = now.discarded_bytes - before.discarded_bytes;
  const std::uint64_t other_bad = (now.bad_header - before.bad_header) + (now.bad_count - before.bad_count) +
                                  (now.timeouts - before.timeouts);
  std::string out = std::to_string(handshake_bytes_) + " bytes came back: ";
  if (bad_checksum > 0) {
    out += std::to_string(bad_checksum) + " packets with bad checksums (a noisy line, or a wrong baud rate?)";
  } else if (packets == 0) {
    out += "garbage, no ARCOS packet (" + std::to_string(garbage) + " bytes skipped; not a Pioneer, or a wrong "
           "baud rate?)";
  } else {
    out += std::to_string(packets) + " packets, none the SYNC echo expected";
  }
  if (other_bad > 0) out += ", " + std::to_string(other_bad) + " malformed frames";
  return out;
}

Status ArcosClient::read_and_dispatch(int timeout_ms) {
  std::array<std::uint8_t, 512> buffer{};
  auto got = stream_->read_some(buffer, timeout_ms);
  if (!got) return got.error();
  if (got.value() == 0) {
    decoder_.expire(clock_.now_us());
  } else {
    decoder_.feed(std::span<const std::uint8_t>(buffer.data(), got.value()), clock_.now_us(),
                  [this](const arcos::Packet& p) { inbox_.push_back(p); });
  }
  for (const arcos::Packet& packet : inbox_) handle_packet(packet);
  inbox_.clear();
  return {};
}

void ArcosClient::handle_packet(const arcos::Packet& packet) {
  if (is_sip(packet.id)) {
    handle_sip(packet);
  } else {
    ++stats_.other_packets;
  }
}

void ArcosClient::handle_sip(const arcos::Packet& packet) {
  auto decoded = arcos::decode_sip(packet);
  if (!decoded) {
    ++stats_.bad_sips;
    return;
  }
  const arcos::Sip& sip = decoded.value();
  const arcos::RobotParams& params = info_.params;
  ++stats_.sips;
  last_sip_us_ = clock_.now_us();
  state_.stamp_us = last_sip_us_;
  ++state_.update_count;
  state_.odometry = odometry_.update(sip.xpos, sip.ypos, sip.thpos);
  state_.left_vel_mps = sip.left_vel * params.vel_conv / 1000.0;
  state_.right_vel_mps = sip.right_vel * params.vel_conv / 1000.0;
  state_.trans_vel_mps = (state_.left_vel_mps + state_.right_vel_mps) / 2.0;
  if (sip.rotvel) {
    state_.rot_vel_radps = *sip.rotvel / 10.0 * kPi / 180.0;
  } else {
    // ARIA's fallback: half the wheel-speed difference times DiffConvFactor.
    state_.rot_vel_radps = (sip.right_vel - sip.left_vel) * params.vel_conv / 2.0 * params.diff_conv;
  }
  for (std::size_t i = 0; i < sip.sonar_count && i < sip.sonar.size(); ++i) {
    const arcos::SonarRaw& reading = sip.sonar[i];
    if (reading.number < hal::kSonarCount) {
      state_.sonar_m[reading.number] = reading.range * params.range_conv / 1000.0;
    }
  }
  state_.battery_v = sip.battery_x10 ? *sip.battery_x10 / 10.0 : sip.battery / 10.0;
  state_.flags = sip.flags;
  state_.fault_flags = sip.fault_flags.value_or(0);
  state_.motors_enabled = (sip.flags & arcos::kFlagMotorsEnabled) != 0;
  state_.estop_pressed = (sip.flags & arcos::kFlagEstop) != 0;
  state_.moving = sip.moving;
  state_.left_stall = (sip.stall_bumpers & arcos::kLeftStall) != 0;
  state_.right_stall = (sip.stall_bumpers & arcos::kRightStall) != 0;
  state_.bumpers = static_cast<std::uint16_t>(sip.stall_bumpers & ~(arcos::kLeftStall | arcos::kRightStall));
  if (state_.link == hal::LinkState::link_lost && opened_) {
    // SIPs resumed on the same stream: the link is back.
    state_.link = hal::LinkState::ok;
    state_.why_stopped.clear();
    log::info(config_.log_name, "event=link-restored");
  }
}

Status ArcosClient::send(const arcos::Frame& frame) {
  if (!stream_) return make_error(Error::Code::state, "not connected");
  auto st = stream_->write_all(frame.span());
  if (!st) return st;
  ++stats_.commands_sent;
  last_sent_us_ = clock_.now_us();
  sips_at_last_send_ = stats_.sips;
  return {};
}

std::string ArcosClient::motion_latch_reason() const {
  if (estop_latched_ && !motors_off_why_.empty()) return "emergency stop latched, " + motors_off_why_;
  if (estop_latched_) return "emergency stop latched";
  return motors_off_why_;
}

Status ArcosClient::motion_refused() const {
  const std::string latch = motion_latch_reason();
  return make_error(Error::Code::state,
                    std::string("motion refused: link ") + hal::to_string(state_.link) + (latch.empty() ? "" : ", " + latch));
}

bool ArcosClient::motion_allowed(const char* what) {
  if (stream_ && opened_ && state_.link == hal::LinkState::ok && !estop_latched_ && motors_off_why_.empty()) {
    return true;
  }
  const std::string latch = motion_latch_reason();
  ++stats_.refused_motion;
  log::debug(config_.log_name, std::string("event=motion-refused request=") + what +
                                   " link=" + hal::to_string(state_.link) + (latch.empty() ? "" : " latch=\"" + latch + "\""));
  return false;
}

Status ArcosClient::set_velocity(double trans_mps, double rot_radps) {
  if (!motion_allowed("velocity")) return motion_refused();
  sips_at_motion_request_ = stats_.sips;
  const int vel = round_to_int(trans_mps * 1000.0);
  const int rvel = round_to_int(rot_radps * 180.0 / kPi);
  if (vel != vel_mm_s_ || !motion_active_) {
    if (auto st = send(arcos::encode_command(arcos::Command::vel, vel)); !st) return st;
  }
  if (rvel != rvel_deg_s_ || !motion_active_) {
    if (auto st = send(arcos::encode_command(arcos::Command::rvel, rvel)); !st) return st;
  }
  vel_mm_s_ = vel;
  rvel_deg_s_ = rvel;
  motion_active_ = vel != 0 || rvel != 0;
  return {};
}

Status ArcosClient::send_motion() {
  if (auto st = send(arcos::encode_command(arcos::Command::vel, vel_mm_s_)); !st) return st;
  return send(arcos::encode_command(arcos::Command::rvel, rvel_deg_s_));
}

Status ArcosClient::stop() {
  motion_active_ = false;
  vel_mm_s_ = 0;
  rvel_deg_s_ = 0;
  if (!stream_ || !opened_) return {};  // nothing of ours is moving it; the firmware watchdog holds it
  return send(arcos::encode_command(arcos::Command::stop));
}

Status ArcosClient::emergency_stop() {
  motion_active_ = false;
  vel_mm_s_ = 0;
  rvel_deg_s_ = 0;
  estop_latched_ = true;
  log::warn(config_.log_name, "event=emergency-stop");
  if (!stream_ || !opened_) return {};
  if (auto st = send(arcos::encode_command(arcos::Command::estop, 1)); !st) return st;
  return send(arcos::encode_command(arcos::Command::enable, 0));
}

Status ArcosClient::set_heading(int heading_deg) {
  if (!motion_allowed("heading")) return motion_refused();
  motion_active_ = false;
  return send(arcos::encode_command(arcos::Command::head, heading_deg));
}

Status ArcosClient::move(int distance_mm) {
  if (!motion_allowed("move")) return motion_refused();
  motion_active_ = false;
  return send(arcos::encode_command(arcos::Command::move, distance_mm));
}

Status ArcosClient::enable_motors(bool enable) {
  if (!stream_ || !opened_) return make_error(Error::Code::state, "not connected");
  if (!enable) {
    // Motors going off: no motion from now on, and none repeated by the keep-alive.
    motion_active_ = false;
    vel_mm_s_ = 0;
    rvel_deg_s_ = 0;
    motors_off_why_ = "motors disabled (enable_motors(false))";
  }
  // The connect-time confirmation, reused: a lost ENABLE after connecting
  // would otherwise leave the motors off while every command "succeeds", and a
  // lost ENABLE 0 would leave a robot that was told to stop able to drive.
  const Status st = switch_motors_until_confirmed(enable);
  if (st) {
    if (enable) {
      estop_latched_ = false;
      motors_off_why_.clear();
    }
    log::info(config_.log_name, enable ? "event=motors-enabled" : "event=motors-disabled");
    return {};
  }
  ++stats_.motor_switch_failures;
  if (enable) {
    motors_off_why_ = "motors not enabled: " + st.error().message;
    log::error(config_.log_name, "event=enable-failed why=\"" + st.error().message + "\"");
    return st;
  }
  // Still on after every ENABLE 0: say so loudly, and ask the firmware to halt
  // the wheels at least (ESTOP), in case that packet gets through.
  const Status estop = send(arcos::encode_command(arcos::Command::estop, 1));
  log::error(config_.log_name, "event=disable-failed why=\"" + st.error().message +
                                   "\" motors=maybe-on estop_sent=" + (estop ? "yes" : "no"));
  return st;
}

int ArcosClient::ms_until_keepalive() const {
  const std::int64_t due = last_sent_us_ + std::int64_t{config_.keepalive_ms} * 1000;
  return ms_between(clock_.now_us(), due);
}

void ArcosClient::service_keepalive() {
  if (!stream_ || !opened_) return;
  const bool time_due = clock_.now_us() - last_sent_us_ >= std::int64_t{config_.keepalive_ms} * 1000;
  const bool sips_due = stats_.sips - sips_at_last_send_ >= static_cast<std::uint64_t>(config_.keepalive_sips);
  if (!time_due && !sips_due) return;
  if (motion_active_ && config_.motion_stale_sips > 0 &&
      stats_.sips - sips_at_motion_request_ >= static_cast<std::uint64_t>(config_.motion_stale_sips)) {
    // Nobody has asked for this motion for a while (the caller stalled, or is
    // reading a backlog of SIPs): repeating it would drive on stale
    // decisions. Stop instead; the caller's next set_velocity() resumes.
    log::warn(config_.log_name, "event=stale-motion-stop sips_since_request=" +
                                    std::to_string(stats_.sips - sips_at_motion_request_));
    if (stop()) ++stats_.stale_motion_stops;
    return;
  }
  // Like ARIA: repeat a motion command in force, otherwise PULSE.
  const Status st = motion_active_ ? send_motion() : send(arcos::encode_command(arcos::Command::pulse));
  if (st) ++stats_.keepalives_sent;
}

void ArcosClient::lose_link(const std::string& why) {
  if (state_.link == hal::LinkState::link_lost) return;
  state_.link = hal::LinkState::link_lost;
  state_.why_stopped = why;
  motion_active_ = false;
  vel_mm_s_ = 0;
  rvel_deg_s_ = 0;
  ++stats_.link_losses;
  log::warn(config_.log_name, "event=link-lost why=\"" + why + "\"");
}

void ArcosClient::check_link() {
  if (state_.link != hal::LinkState::ok) return;
  const std::int64_t silence_us = clock_.now_us() - last_sip_us_;
  if (silence_us > std::int64_t{config_.link_loss_ms} * 1000) {
    lose_link("no SIP for " + std::to_string(silence_us / 1000) + " ms");
  }
}

Result<bool> ArcosClient::wait_for_update(int timeout_ms) {
  const std::int64_t deadline = clock_.now_us() + std::int64_t{timeout_ms} * 1000;
  const bool link_down = state_.link == hal::LinkState::link_lost || state_.link == hal::LinkState::disconnected;
  if (link_down && ever_connected_ && config_.auto_reconnect &&
      clock_.now_us() - last_reconnect_attempt_us_ >= std::int64_t{config_.reconnect_interval_ms} * 1000) {
    last_reconnect_attempt_us_ = clock_.now_us();
    if (state_.link == hal::LinkState::disconnected) state_.link = hal::LinkState::link_lost;
    if (connect()) return true;
  }
  if (!stream_) {
    clock_.sleep_until_us(deadline);
    return false;
  }
  const std::uint64_t start_count = state_.update_count;
  while (true) {
    service_keepalive();
    const std::int64_t now = clock_.now_us();
    int wait_ms = ms_between(now, deadline);
    if (opened_) wait_ms = std::min(wait_ms, ms_until_keepalive());
    if (state_.link == hal::LinkState::ok) {
      wait_ms = std::min(wait_ms, ms_between(now, last_sip_us_ + std::int64_t{config_.link_loss_ms} * 1000 + 1000));
    }
    const Status st = read_and_dispatch(wait_ms);
    service_keepalive();  // SIPs just read may make a keep-alive due
    if (!st) {
      lose_link(st.error().message);
      stream_->close();
      stream_.reset();
      opened_ = false;
      return state_.update_count != start_count;
    }
    check_link();
    if (state_.update_count != start_count) return true;
    if (clock_.now_us() >= deadline) return false;
  }
}

Status ArcosClient::disconnect() {
  if (!stream_) {
    if (state_.link != hal::LinkState::link_lost) state_.link = hal::LinkState::disconnected;
    return {};
  }
  Status result;
  if (opened_) {
    // The reference's clean shutdown: motors off, a short grace, then CLOSE.
    result = send(arcos::encode_command(arcos::Command::enable, 0));
    clock_.sleep_until_us(clock_.now_us() + std::int64_t{config_.close_grace_ms} * 1000);
    const Status closed = send(arcos::encode_command(arcos::Command::close, 1));
    if (result) result = closed;
  }
  stream_->close();
  stream_.reset();
  opened_ = false;
  motion_active_ = false;
  state_.link = hal::LinkState::disconnected;
  state_.why_stopped = "disconnected by client";
  log::info(config_.log_name, "event=disconnected");
  return result;
}

}  // namespace p3at::bridge
