#pragma once
/// Per-cycle timing of the executive: compute time (measured with
/// std::chrono::steady_clock around cycle(), for measurement only), overruns
/// (compute time longer than the period) and missed updates (cycles run without
/// a new drive update). Percentiles come from the latest kWindow samples kept in
/// a fixed-size ring: no allocation after construction.

#include <array>
#include <cstddef>
#include <cstdint>

namespace p3at::exec {

class CycleStats {
 public:
  /// Samples kept for the percentiles (the latest ones).
  static constexpr std::size_t kWindow = 1024;

  /// `period_us`: the cycle period; a compute time above it is an overrun.
  explicit CycleStats(std::int64_t period_us = 100'000) : period_us_(period_us) {}

  /// Records one cycle: its compute time (µs) and whether no new update had arrived.
  void record(double compute_us, bool missed_update);

  std::uint64_t cycles() const { return cycles_; }
  std::uint64_t overruns() const { return overruns_; }
  std::uint64_t missed_updates() const { return missed_updates_; }
  /// Records a stall: a gap between two cycles of `missed_cycles` periods or
  /// more (the process was stopped, or starved of CPU), lasting `stall_ms`.
  void record_stall(std::uint64_t missed_cycles, std::int64_t stall_ms);
  std::uint64_t stalls() const { return stalls_; }
  /// Cycles the executive did not run because of stalls (summed).
  std::uint64_t missed_cycles() const { return missed_cycles_; }
  std::int64_t longest_stall_ms() const { return longest_stall_ms_; }
  /// Longest compute time ever recorded, µs.
  double max_us() const { return max_us_; }
  std::int64_t period_us() const { return period_us_; }

  /// The p-quantile (p in [0, 1]) of the compute times in the window, by nearest
  /// rank (the smallest sample with at least p of the window at or below it); 0
  /// with no samples.
  double percentile_us(double p) const;
  double p50_us() const { return percentile_us(0.50); }
  double p99_us() const { return percentile_us(0.99); }

 private:
  std::int64_t period_us_;
  std::array<double, kWindow> samples_{};
  std::size_t next_ = 0;    ///< ring write position
  std::size_t filled_ = 0;  ///< samples in the ring, up to kWindow
  std::uint64_t cycles_ = 0;
  std::uint64_t overruns_ = 0;
  std::uint64_t missed_updates_ = 0;
  std::uint64_t stalls_ = 0;
  std::uint64_t missed_cycles_ = 0;
  std::int64_t longest_stall_ms_ = 0;
  double max_us_ = 0.0;
};

}  // namespace p3at::exec
