#include "p3at/sim/can/sim_gyro.hpp"

#include <algorithm>

namespace p3at::sim {
namespace {

// Stream id for the gyro's noise, so it never shares draws with other devices of the same seed.
constexpr std::uint64_t kGyroStream = 0x6779726FULL;
// After a long stall, catch up at most this many samples, then skip ahead
// (the counter still advances, as a node whose frames were lost would).
constexpr int kMaxCatchUp = 100;

}  // namespace

SimGyro::SimGyro(SimGyroConfig config)
    : config_(config),
      node_(config.node_id, config.heartbeat_period_us, config.auto_start),
      rng_(config.seed, kGyroStream) {
  if (config_.period_us <= 0) config_.period_us = can::kGyroPdoPeriodUs;
}

void SimGyro::set_fault(bool fault, std::uint16_t code) {
  if (fault == fault_) return;
  fault_ = fault;
  emcy_pending_ = true;
  emcy_code_ = fault ? code : can::emcy_code::kNoError;
}

Status SimGyro::step(hal::CanBus& bus, std::int64_t now_us, double true_rate_radps) {
  if (!started_) {
    started_ = true;
    first_step_us_ = now_us;
  }
  if (auto st = node_.step(bus, now_us); !st) return st;
  if (node_.generation() != generation_seen_) {
    generation_seen_ = node_.generation();
    counter_ = 0;
    next_sample_us_ = now_us + config_.period_us;
  }
  if (node_.silent()) return {};
  if (emcy_pending_) {
    can::Emergency emcy;
    emcy.error_code = emcy_code_;
    emcy.error_register = fault_ ? can::error_register::kGeneric : 0;
    if (auto st = bus.send(can::encode_emcy(config_.node_id, emcy)); !st) return st;
    emcy_pending_ = false;
  }
  if (!node_.operational()) {
    next_sample_us_ = std::max(next_sample_us_, now_us);
    return {};
  }
  int sent = 0;
  while (next_sample_us_ <= now_us) {
    next_sample_us_ += config_.period_us;
    const double age_s = static_cast<double>(next_sample_us_ - first_step_us_) * 1e-6;
    const double measured = (1.0 + config_.scale_error) * true_rate_radps + config_.bias_radps +
                            config_.bias_drift_radps_per_s * age_s + rng_.gaussian(config_.noise_sd_radps);
    can::GyroSample sample;
    sample.yaw_rate_radps = std::clamp(measured, -config_.range_radps, config_.range_radps);
    sample.saturated = sample.yaw_rate_radps != measured;
    sample.temperature_c = config_.temperature_c;
    sample.counter = counter_++;
    sample.fault = fault_;
    last_measured_radps_ = sample.yaw_rate_radps;
    if (++sent > kMaxCatchUp) continue;  // lost: counted by the receiver as a counter gap
    if (auto st = bus.send(can::encode_gyro_pdo(config_.node_id, sample)); !st) return st;
    ++samples_sent_;
  }
  return {};
}

}  // namespace p3at::sim
