#pragma once
/// Yaw-rate integration with bias estimation while the robot stands still.

#include <cstdint>
#include <vector>

namespace p3at::bridge {

struct GyroIntegratorConfig {
  double sample_period_s = 0.01;       ///< the gyro's sample period: counter steps → time
  double settle_s = 0.2;               ///< standing still this long before samples teach the bias
  double bias_time_constant_s = 20.0;  ///< once warmed up, the bias follows a moving average this slow
  double min_learning_s = 1.0;         ///< bias_valid() after this much standstill data
  double max_still_deviation_radps = 0.05;  ///< a "still" sample this far from the bias is not learned (robot carried)
  std::uint32_t max_bridged_steps = 50;     ///< longer gaps (in samples) are not integrated across
};

/// Integrates bias-corrected yaw rate into a continuous heading (radians,
/// counter-clockwise positive, not wrapped). While the drive base reports
/// standstill, samples are held back; when a later report confirms the robot
/// was still when they were taken, they teach the bias and their integrated
/// drift is taken back out of the heading (a zero-velocity update). A report of
/// motion discards them from learning and keeps their integration.
/// Not thread-safe; fed from one loop.
class GyroIntegrator {
 public:
  explicit GyroIntegrator(GyroIntegratorConfig config = {});

  /// The drive base's standstill report at `now_us` (steady µs, the samples' clock).
  void set_standstill(bool still, std::int64_t now_us);

  /// One sample, `steps` sample periods after the previous one (1 normally,
  /// more after lost samples; 0 is ignored), taken at `stamp_us`.
  void add_sample(double rate_radps, std::uint32_t steps, std::int64_t stamp_us);

  /// Sets the integrated heading (the bias estimate is kept).
  void reset_heading(double heading_rad) { heading_rad_ = heading_rad; }

  double heading_rad() const { return heading_rad_; }
  double bias_radps() const { return bias_radps_; }
  /// True once min_learning_s of standstill samples have been learned.
  bool bias_valid() const;
  double learned_s() const { return static_cast<double>(learned_samples_) * config_.sample_period_s; }
  /// The latest sample minus the bias.
  double corrected_rate_radps() const { return last_rate_radps_ - bias_radps_; }
  std::int64_t last_sample_us() const { return last_sample_us_; }
  std::uint64_t samples() const { return samples_; }
  std::uint64_t unbridged_gaps() const { return unbridged_gaps_; }
  std::uint64_t rejected_still_samples() const { return rejected_still_; }

 private:
  struct Pending {
    double rate_radps;
    double increment_rad;  // what this sample added to the heading
    double dt_s;
    std::int64_t stamp_us;
  };
  void commit_pending(std::int64_t confirmed_until_us);
  void learn(double rate_radps, double dt_s);

  GyroIntegratorConfig config_;
  double heading_rad_ = 0.0;
  double bias_radps_ = 0.0;
  double last_rate_radps_ = 0.0;
  std::int64_t last_sample_us_ = 0;
  bool still_ = false;
  std::int64_t still_since_us_ = 0;
  std::vector<Pending> pending_;
  std::uint64_t learned_samples_ = 0;
  std::uint64_t samples_ = 0;
  std::uint64_t unbridged_gaps_ = 0;
  std::uint64_t rejected_still_ = 0;
};

}  // namespace p3at::bridge
