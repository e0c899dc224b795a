#include "engine/time_position.hpp"

#include <algorithm>
#include <cmath>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {
namespace {

bool same_time(const Mixture1& a, const Mixture1& b) {
  const double ma = a.mean(), mb = b.mean(), va = a.variance(), vb = b.variance();
  if (!std::isfinite(ma) || !std::isfinite(mb) || !std::isfinite(va) || !std::isfinite(vb)) return false;
  return std::abs(ma - mb) <= 1e-9 * (1.0 + std::abs(ma)) && std::abs(va - vb) <= 1e-9 * (1.0 + va);
}

}  // namespace

std::optional<std::size_t> time_coupled_robot(const Branch& b) {
  std::optional<std::size_t> found;
  std::size_t last = 0;
  for (std::size_t i = 0; i < b.robots.size(); ++i) {
    const RobotOutcome& r = b.robots[i];
    if (!r.finished || !same_time(r.finish_time_s, b.completion_time_s)) continue;
    ++last;
    if (!r.final_time_scores.empty() && r.final_time_scores.size() == r.final_components.size() &&
        r.time_score_correlation > 0.0) {
      found = i;
    }
  }
  // Two robots finishing as the completion: which one's paths the time
  // follows is not known; keep both independent.
  return last == 1 ? found : std::nullopt;
}

double time_given_score(double p_time, double rho, double z) {
  if (!(p_time > 0.0)) return 0.0;
  if (!(p_time < 1.0)) return 1.0;
  if (!(rho > 0.0)) return p_time;
  const double q = normal_quantile(p_time);
  return normal_cdf((q - rho * z) / std::sqrt(1.0 - rho * rho));
}

BranchRadii::BranchRadii(const Branch& b, const mission::Mission& mission, const std::vector<double>& rmax) {
  const std::optional<std::size_t> c = time_coupled_robot(b);
  coupled_ = c.has_value();
  if (coupled_) {
    rho_ = b.robots[*c].time_score_correlation;
    scores_ = b.robots[*c].final_time_scores;
    for (std::size_t k = 0; k < scores_.size(); ++k) weights_.push_back(component_weight(b.robots[*c], k));
  }
  for (const double r : rmax) {
    double others = 1.0;
    std::vector<double> parts;
    for (std::size_t i = 0; i < b.robots.size(); ++i) {
      const RobotOutcome& robot = b.robots[i];
      const Eigen::Vector2d goal(mission.robots[i].goal.x_m, mission.robots[i].goal.y_m);
      if (coupled_ && i == *c) {
        for (std::size_t k = 0; k < robot.final_components.size(); ++k) {
          parts.push_back(component_weight(robot, k) * probability_within(robot.final_components[k], goal, r));
        }
      } else if (others > 0.0) {
        others *= final_within(robot, goal, r);
      }
    }
    double coupled = 1.0;
    if (coupled_) {
      coupled = 0.0;
      for (const double p : parts) coupled += p;
    }
    radius_.push_back(others * coupled);
    others_.push_back(others);
    within_.push_back(std::move(parts));
  }
}

double BranchRadii::joint(double p_time, std::size_t j) const {
  const double independent = p_time * radius_[j];
  if (!coupled_ || !(p_time > 0.0) || !(p_time < 1.0)) return independent;
  // P(t <= T | component k), rescaled so that over the components they
  // average to P(t <= T) exactly (a handful of points stand for the paths'
  // circle: the copula's margin over them is off by a little).
  std::vector<double> given(scores_.size());
  double margin = 0.0;
  for (std::size_t k = 0; k < scores_.size(); ++k) {
    given[k] = time_given_score(p_time, rho_, scores_[k]);
    margin += weights_[k] * given[k];
  }
  if (!(margin > 0.0)) return independent;
  double joint = 0.0;
  for (std::size_t k = 0; k < scores_.size(); ++k) joint += std::min(1.0, given[k] * p_time / margin) * within_[j][k];
  joint *= others_[j];
  // Never past what the two curves allow (Frechet bounds).
  return std::clamp(joint, std::max(0.0, p_time + radius_[j] - 1.0), std::min(p_time, radius_[j]));
}

}  // namespace p3at::verifier::engine
