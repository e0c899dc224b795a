#include "p3at/sim/can/sim_safety_node.hpp"

#include <algorithm>

namespace p3at::sim {

SimSafetyNode::SimSafetyNode(SimSafetyNodeConfig config)
    : config_(config), node_(config.node_id, config.heartbeat_period_us, config.auto_start) {
  if (config_.period_us <= 0) config_.period_us = can::kSafetyPdoPeriodUs;
}

void SimSafetyNode::press_estop(bool pressed) {
  changed_ = changed_ || state_.estop_pressed != pressed;
  state_.estop_pressed = pressed;
}

void SimSafetyNode::set_bumpers(std::uint8_t bumpers) {
  changed_ = changed_ || state_.bumpers != bumpers;
  state_.bumpers = bumpers;
}

void SimSafetyNode::set_fault(bool fault, std::uint16_t code) {
  if (fault == state_.fault) return;
  state_.fault = fault;
  changed_ = true;
  emcy_pending_ = true;
  emcy_code_ = fault ? code : can::emcy_code::kNoError;
}

Status SimSafetyNode::step(hal::CanBus& bus, std::int64_t now_us) {
  if (auto st = node_.step(bus, now_us); !st) return st;
  if (node_.generation() != generation_seen_) {
    generation_seen_ = node_.generation();
    state_.counter = 0;
    next_state_us_ = now_us;
  }
  if (node_.silent()) return {};
  if (emcy_pending_) {
    can::Emergency emcy;
    emcy.error_code = emcy_code_;
    emcy.error_register = state_.fault ? can::error_register::kManufacturer : 0;
    if (auto st = bus.send(can::encode_emcy(config_.node_id, emcy)); !st) return st;
    emcy_pending_ = false;
  }
  if (!node_.operational()) {
    next_state_us_ = std::max(next_state_us_, now_us);
    return {};
  }
  if (!changed_ && now_us < next_state_us_) return {};
  // One message reports the present state however late we are; the period restarts from now.
  changed_ = false;
  next_state_us_ = now_us + config_.period_us;
  if (auto st = bus.send(can::encode_safety_pdo(config_.node_id, state_)); !st) return st;
  ++state_.counter;
  ++states_sent_;
  return {};
}

}  // namespace p3at::sim
