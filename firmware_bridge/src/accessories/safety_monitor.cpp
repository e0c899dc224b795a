#include "p3at/bridge/accessories/safety_monitor.hpp"

#include <cstdio>

namespace p3at::bridge {
namespace {

std::string hex16(unsigned value) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", value & 0xFFFFu);
  return text;
}

std::string bumper_text(std::uint8_t bumpers) {
  std::string out;
  if ((bumpers & 0x0Fu) != 0) out += "front " + hex16(bumpers & 0x0Fu);
  if ((bumpers & 0xF0u) != 0) out += std::string(out.empty() ? "" : ", ") + "rear " + hex16((bumpers >> 4) & 0x0Fu);
  return out;
}

}  // namespace

SafetyMonitor::SafetyMonitor(std::uint8_t node_id, SafetyMonitorConfig config) : node_id_(node_id), config_(config) {}

void SafetyMonitor::on_state(const can::SafetyState& state, std::int64_t stamp_us) {
  state_ = state;
  state_us_ = stamp_us;
}

void SafetyMonitor::on_heartbeat(can::NmtState state, std::int64_t stamp_us) {
  nmt_ = state;
  heartbeat_us_ = stamp_us;
  if (state == can::NmtState::boot_up) {
    // A restarted node's earlier state and emergencies no longer describe it.
    state_.reset();
    emergency_.reset();
  }
}

void SafetyMonitor::on_emergency(const can::Emergency& emergency) {
  if (emergency.error_code == can::emcy_code::kNoError) {
    emergency_.reset();
  } else {
    emergency_ = emergency;
  }
}

void SafetyMonitor::on_bus_state(hal::CanBusState state, const std::string& detail) {
  bus_ = state;
  bus_detail_ = detail;
}

std::optional<std::string> SafetyMonitor::blocking_reason(std::int64_t now_us) const {
  const std::string node = "safety node " + std::to_string(node_id_);
  if (!hal::can_communicate(bus_)) {
    return "CAN bus " + std::string(hal::to_string(bus_)) + (bus_detail_.empty() ? "" : " (" + bus_detail_ + ")");
  }
  // Fresh reports of a stop request come first: they are the reason a person wants to read.
  const std::int64_t state_limit_us = config_.state_period_us * config_.missed_states;
  const bool state_fresh = state_ && now_us - state_us_ <= state_limit_us;
  if (state_fresh && state_->estop_pressed) return "e-stop pressed on " + node;
  if (state_fresh && state_->bumpers != 0) return "bumper hit on " + node + " (" + bumper_text(state_->bumpers) + ")";
  if (state_fresh && state_->fault) return node + " reports a fault";
  if (emergency_) {
    return node + " EMCY " + hex16(emergency_->error_code) + " (" + can::describe_emcy_code(emergency_->error_code) + ")";
  }
  const std::int64_t heartbeat_limit_us = config_.heartbeat_period_us * config_.missed_heartbeats;
  if (!nmt_) return "no heartbeat from " + node + " yet";
  if (now_us - heartbeat_us_ > heartbeat_limit_us) {
    return node + " heartbeat missing for " + std::to_string((now_us - heartbeat_us_) / 1000) + " ms (limit " +
           std::to_string(config_.missed_heartbeats) + " periods of " +
           std::to_string(config_.heartbeat_period_us / 1000) + " ms)";
  }
  if (*nmt_ != can::NmtState::operational) return node + " is " + can::to_string(*nmt_) + ", not operational";
  if (!state_) return "no state from " + node + " yet";
  if (!state_fresh) {
    return node + " state stale for " + std::to_string((now_us - state_us_) / 1000) + " ms (limit " +
           std::to_string(state_limit_us / 1000) + " ms)";
  }
  return std::nullopt;
}

SafetyVerdict SafetyMonitor::evaluate(std::int64_t now_us) {
  SafetyVerdict verdict;
  const std::optional<std::string> reason = blocking_reason(now_us);
  if (armed_ && reason) {
    armed_ = false;
    trip_why_ = *reason;
    ++trips_;
    last_trip_ = SafetyTrip{now_us, state_stamp_us(), heartbeat_stamp_us(), *reason};
    verdict.stop_now = true;
  }
  verdict.motion_allowed = armed_;
  verdict.clear = !reason;
  if (!armed_) {
    verdict.why = trip_why_;
    if (reason && *reason != trip_why_) verdict.why += "; now: " + *reason;
    if (!reason) verdict.why += "; clear now, waiting for re-arm";
  }
  return verdict;
}

Status SafetyMonitor::rearm(std::int64_t now_us) {
  if (const std::optional<std::string> reason = blocking_reason(now_us)) {
    return make_error(Error::Code::state, "cannot re-arm: " + *reason);
  }
  armed_ = true;
  trip_why_.clear();
  return {};
}

}  // namespace p3at::bridge
