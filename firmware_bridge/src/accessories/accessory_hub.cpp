#include "p3at/bridge/accessories/accessory_hub.hpp"

#include <cmath>

#include "p3at/protocols/can/canopen.hpp"

namespace p3at::bridge {
namespace {

// A counter may legitimately jump anywhere after a silence this long (half its range).
constexpr std::int64_t kResyncPeriods = 64;
// Wheel speeds below these count as standing still.
constexpr double kStillTransMps = 0.002;
constexpr double kStillRotRadps = 0.002;

}  // namespace

AccessoryHub::AccessoryHub(hal::CanBus& bus, AccessoryConfig config)
    : bus_(bus),
      config_(config),
      gyro_(config.gyro),
      fuser_(config.fusion),
      safety_(config.safety_node_id, config.safety) {}

bool AccessoryHub::is_standstill(const hal::DriveState& state) {
  return !state.moving && std::fabs(state.left_vel_mps) < kStillTransMps &&
         std::fabs(state.right_vel_mps) < kStillTransMps && std::fabs(state.trans_vel_mps) < kStillTransMps &&
         std::fabs(state.rot_vel_radps) < kStillRotRadps;
}

Status AccessoryHub::start() {
  auto frame = can::encode_nmt(can::NmtCommand::start, 0);
  if (!frame) return frame.error();
  if (auto st = bus_.send(*frame); !st) {
    ++counters_.send_failures;
    return st;
  }
  ++counters_.nmt_sent;
  return {};
}

void AccessoryHub::send_nmt_start(std::uint8_t node_id, std::int64_t now_us) {
  const std::size_t slot = node_id == config_.gyro_node_id ? 0 : 1;
  // One start per heartbeat period is plenty; a node that ignores it keeps blocking motion anyway.
  if (now_us - last_nmt_sent_us_[slot] < config_.safety.heartbeat_period_us) return;
  last_nmt_sent_us_[slot] = now_us;
  auto frame = can::encode_nmt(can::NmtCommand::start, node_id);
  if (!frame || !bus_.send(*frame)) {
    ++counters_.send_failures;
    return;
  }
  ++counters_.nmt_sent;
}

SafetyVerdict AccessoryHub::poll(std::int64_t now_us) {
  for (std::size_t i = 0; i < config_.max_frames_per_poll; ++i) {
    auto rx = bus_.receive();
    if (!rx) {
      ++counters_.receive_errors;
      break;
    }
    if (!rx->has_value()) break;
    handle(**rx, now_us);
  }
  const hal::CanBusStatus& status = bus_.status();
  safety_.on_bus_state(status.state, status.last_error);
  return safety_.evaluate(now_us);
}

void AccessoryHub::handle(const hal::CanRxFrame& rx, std::int64_t now_us) {
  ++counters_.frames;
  const can::CobId cob = can::classify(rx.frame);
  const bool gyro = cob.node_id == config_.gyro_node_id;
  const bool safety = cob.node_id == config_.safety_node_id;
  switch (cob.kind) {
    case can::MessageKind::nmt:
    case can::MessageKind::sync:
      ++counters_.ignored;
      return;
    case can::MessageKind::tpdo1:
      if (gyro) return handle_gyro_pdo(rx);
      if (safety) return handle_safety_pdo(rx);
      break;
    case can::MessageKind::heartbeat:
      if (gyro || safety) return handle_heartbeat(cob.node_id, rx, now_us);
      break;
    case can::MessageKind::emcy:
      if (gyro || safety) return handle_emcy(cob.node_id, rx);
      break;
    case can::MessageKind::other:
      break;
  }
  ++counters_.unknown_id;
}

void AccessoryHub::handle_gyro_pdo(const hal::CanRxFrame& rx) {
  if (rx.frame.length != can::kGyroPdoLength) {
    ++counters_.wrong_length;
    return;
  }
  auto sample = can::decode_gyro_pdo(rx.frame);
  if (!sample) {
    ++counters_.bad_payload;
    return;
  }
  if (rx.stamp_us - last_gyro_frame_us_ > kResyncPeriods * config_.gyro_period_us) gyro_seq_.reset();
  const std::uint32_t steps = gyro_seq_.accept(sample->counter);
  if (steps == 0) {
    ++counters_.stale_counter;
    return;
  }
  last_gyro_frame_us_ = rx.stamp_us;
  ++counters_.gyro_samples;
  counters_.gyro_lost_samples += steps - 1;
  gyro_fault_flag_ = sample->fault;
  if (sample->fault) return;  // the sensor says the rate is not to be trusted
  gyro_.add_sample(sample->yaw_rate_radps, steps, rx.stamp_us);
}

void AccessoryHub::handle_safety_pdo(const hal::CanRxFrame& rx) {
  if (rx.frame.length != can::kSafetyPdoLength) {
    ++counters_.wrong_length;
    return;
  }
  auto state = can::decode_safety_pdo(rx.frame);
  if (!state) {
    ++counters_.bad_payload;
    return;
  }
  if (rx.stamp_us - last_safety_frame_us_ > kResyncPeriods * config_.safety.state_period_us) safety_seq_.reset();
  if (safety_seq_.accept(state->counter) == 0) {
    ++counters_.stale_counter;
    return;
  }
  last_safety_frame_us_ = rx.stamp_us;
  ++counters_.safety_states;
  safety_.on_state(*state, rx.stamp_us);
}

void AccessoryHub::handle_heartbeat(std::uint8_t node_id, const hal::CanRxFrame& rx, std::int64_t now_us) {
  if (rx.frame.length != can::kHeartbeatLength) {
    ++counters_.wrong_length;
    return;
  }
  auto state = can::decode_heartbeat(rx.frame);
  if (!state) {
    ++counters_.bad_payload;
    return;
  }
  ++counters_.heartbeats;
  if (node_id == config_.gyro_node_id) {
    gyro_nmt_ = *state;
    if (*state == can::NmtState::boot_up) {
      gyro_seq_.reset();
      gyro_emergency_.reset();
      gyro_fault_flag_ = false;
    }
  } else {
    safety_.on_heartbeat(*state, rx.stamp_us);
    if (*state == can::NmtState::boot_up) safety_seq_.reset();
  }
  if (config_.start_nodes && (*state == can::NmtState::boot_up || *state == can::NmtState::pre_operational)) {
    send_nmt_start(node_id, now_us);
  }
}

void AccessoryHub::handle_emcy(std::uint8_t node_id, const hal::CanRxFrame& rx) {
  if (rx.frame.length != can::kEmcyLength) {
    ++counters_.wrong_length;
    return;
  }
  auto emergency = can::decode_emcy(rx.frame);
  if (!emergency) {
    ++counters_.bad_payload;
    return;
  }
  ++counters_.emergencies;
  if (node_id == config_.gyro_node_id) {
    if (emergency->error_code == can::emcy_code::kNoError) {
      gyro_emergency_.reset();
    } else {
      gyro_emergency_ = *emergency;
    }
  } else {
    safety_.on_emergency(*emergency);
  }
}

std::string AccessoryHub::gyro_problem(std::int64_t now_us) const {
  if (!hal::can_communicate(bus_.status().state)) return "CAN bus " + std::string(hal::to_string(bus_.status().state));
  if (counters_.gyro_samples == 0) return "no gyro samples yet";
  const std::int64_t limit_us = config_.gyro_period_us * config_.gyro_missed_samples;
  if (now_us - last_gyro_frame_us_ > limit_us) {
    return "gyro silent for " + std::to_string((now_us - last_gyro_frame_us_) / 1000) + " ms";
  }
  if (gyro_fault_flag_) return "gyro reports a sensor fault";
  if (gyro_emergency_) return std::string("gyro EMCY: ") + can::describe_emcy_code(gyro_emergency_->error_code);
  if (gyro_nmt_ && *gyro_nmt_ != can::NmtState::operational) {
    return std::string("gyro is ") + can::to_string(*gyro_nmt_);
  }
  if (!gyro_.bias_valid()) return "gyro bias not learned yet (the robot must stand still)";
  return {};
}

bool AccessoryHub::gyro_usable(std::int64_t now_us) const { return gyro_problem(now_us).empty(); }

hal::Pose2 AccessoryHub::aided_pose(const hal::Pose2& odometry, std::int64_t stamp_us) {
  std::optional<double> gyro_heading;
  if (gyro_usable(stamp_us)) gyro_heading = gyro_.heading_rad();
  return fuser_.update(odometry, gyro_heading, stamp_us);
}

}  // namespace p3at::bridge
