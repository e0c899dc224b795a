#include "p3at/executive/cycle_stats.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::exec {

void CycleStats::record(double compute_us, bool missed_update) {
  ++cycles_;
  if (compute_us > static_cast<double>(period_us_)) ++overruns_;
  if (missed_update) ++missed_updates_;
  max_us_ = std::max(max_us_, compute_us);
  samples_[next_] = compute_us;
  next_ = (next_ + 1) % kWindow;
  filled_ = std::min(filled_ + 1, kWindow);
}

void CycleStats::record_stall(std::uint64_t missed_cycles, std::int64_t stall_ms) {
  ++stalls_;
  missed_cycles_ += missed_cycles;
  longest_stall_ms_ = std::max(longest_stall_ms_, stall_ms);
}

double CycleStats::percentile_us(double p) const {
  if (filled_ == 0) return 0.0;
  // A copy on the stack (8 KiB), so the statistics stay const and allocation-free.
  std::array<double, kWindow> sorted = samples_;
  const auto first = sorted.begin();
  const auto last = first + static_cast<std::ptrdiff_t>(filled_);
  const double clamped = std::clamp(p, 0.0, 1.0);
  const double rank = std::ceil(clamped * static_cast<double>(filled_));
  const std::size_t index = rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
  const auto nth = first + static_cast<std::ptrdiff_t>(index);
  std::nth_element(first, nth, last);
  return *nth;
}

}  // namespace p3at::exec
