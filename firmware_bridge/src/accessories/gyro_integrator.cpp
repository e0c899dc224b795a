#include "p3at/bridge/accessories/gyro_integrator.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::bridge {
namespace {

// Held-back samples are bounded: without standstill confirmations for this
// many samples (e.g. the drive base stopped reporting) the oldest are dropped
// from learning; their integration already happened.
constexpr std::size_t kMaxPending = 512;

}  // namespace

GyroIntegrator::GyroIntegrator(GyroIntegratorConfig config) : config_(config) { pending_.reserve(64); }

bool GyroIntegrator::bias_valid() const { return learned_s() + 1e-9 >= config_.min_learning_s; }

void GyroIntegrator::set_standstill(bool still, std::int64_t now_us) {
  if (!still) {
    still_ = false;
    pending_.clear();  // they may have been taken while moving: keep their integration, learn nothing
    return;
  }
  if (!still_) {
    still_ = true;
    still_since_us_ = now_us;
    // Samples taken before this report cannot be confirmed as still.
    pending_.clear();
    return;
  }
  commit_pending(now_us);
}

void GyroIntegrator::add_sample(double rate_radps, std::uint32_t steps, std::int64_t stamp_us) {
  if (steps == 0 || !std::isfinite(rate_radps)) return;
  ++samples_;
  last_rate_radps_ = rate_radps;
  last_sample_us_ = stamp_us;
  if (steps > config_.max_bridged_steps) {
    // Too long a gap to assume the rate held; integrate only this sample's own period.
    ++unbridged_gaps_;
    steps = 1;
  }
  const double dt_s = static_cast<double>(steps) * config_.sample_period_s;
  const double increment = (rate_radps - bias_radps_) * dt_s;
  heading_rad_ += increment;
  if (still_ && stamp_us >= still_since_us_ + static_cast<std::int64_t>(config_.settle_s * 1e6)) {
    if (pending_.size() == kMaxPending) pending_.erase(pending_.begin());
    pending_.push_back(Pending{rate_radps, increment, dt_s, stamp_us});
  }
}

void GyroIntegrator::commit_pending(std::int64_t confirmed_until_us) {
  std::size_t used = 0;
  for (const Pending& p : pending_) {
    if (p.stamp_us > confirmed_until_us) break;  // not yet confirmed by a report after it
    ++used;
    if (std::fabs(p.rate_radps - bias_radps_) > config_.max_still_deviation_radps) {
      ++rejected_still_;  // the wheels were still but the body turned: carried, or on a turntable
      continue;
    }
    heading_rad_ -= p.increment_rad;  // the robot did not turn: this was drift
    learn(p.rate_radps, p.dt_s);
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(used));
}

void GyroIntegrator::learn(double rate_radps, double dt_s) {
  // Plain mean at first (fast convergence), then an exponential moving average
  // with the configured time constant (follows temperature drift).
  const double mean_weight = 1.0 / static_cast<double>(learned_samples_ + 1);
  const double ema_weight = dt_s / (config_.bias_time_constant_s + dt_s);
  const double alpha = std::max(mean_weight, ema_weight);
  bias_radps_ += alpha * (rate_radps - bias_radps_);
  ++learned_samples_;
}

}  // namespace p3at::bridge
