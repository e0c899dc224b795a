#include "engine/moved_start.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::verifier::engine {

double share_still_ahead(const Eigen::Vector2d& analysis_start, const std::optional<Eigen::Vector2d>& goal,
                         const Eigen::Vector2d& point) {
  if (!goal) return 1.0;
  const Eigen::Vector2d leg = *goal - analysis_start;
  const double length2 = leg.squaredNorm();
  // Starting on the goal there is no way ahead to share out: the robot stays.
  if (!(length2 > 1e-12)) return 1.0;
  const double along = (point - analysis_start).dot(leg) / length2;
  return 1.0 - std::clamp(along, 0.0, 1.0);
}

bool close_enough_to_merge(const Eigen::Vector2d& mean_a, const Eigen::Matrix2d& cov_a, const Eigen::Vector2d& mean_b,
                           const Eigen::Matrix2d& cov_b) {
  constexpr double kFloorM = 0.02;
  constexpr double kSpreads = 2.0;
  const Eigen::Vector2d apart = mean_b - mean_a;
  const double distance = apart.norm();
  if (distance <= kFloorM) return true;
  const Eigen::Vector2d along = apart / distance;
  const double sd_a = std::sqrt(std::max(0.0, along.dot(cov_a * along)));
  const double sd_b = std::sqrt(std::max(0.0, along.dot(cov_b * along)));
  return distance <= kSpreads * (sd_a + sd_b) + kFloorM;
}

}  // namespace p3at::verifier::engine
