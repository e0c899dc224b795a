#include "engine/leg_trajectory.hpp"

#include <cmath>
#include <cstddef>

namespace p3at::verifier::engine {

double LegTrajectory::path_time(double t_s) const {
  if (path_time_s.empty() || !(t_s > 0.0)) return t_s;
  const double last = static_cast<double>(path_time_s.size() - 1);
  // Past the last matched second the paths go on at their own pace.
  if (t_s >= last) return path_time_s.back() + (t_s - last);
  const auto i = static_cast<std::size_t>(std::floor(t_s));
  const double f = t_s - static_cast<double>(i);
  return path_time_s[i] + f * (path_time_s[i + 1] - path_time_s[i]);
}

Eigen::Matrix2d LegTrajectory::redrawn_cov(double t_s) const {
  const double last = static_cast<double>(redrawn_cov_m2.size() - 1);
  if (!(t_s > 0.0)) return redrawn_cov_m2.front();
  if (t_s >= last) return redrawn_cov_m2.back();
  const auto i = static_cast<std::size_t>(std::floor(t_s));
  const double f = t_s - static_cast<double>(i);
  return (1.0 - f) * redrawn_cov_m2[i] + f * redrawn_cov_m2[i + 1];
}

}  // namespace p3at::verifier::engine
