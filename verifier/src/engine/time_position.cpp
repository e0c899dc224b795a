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

bool has_time_scores(const RobotOutcome& r) {
  return !r.final_time_scores.empty() && r.final_time_scores.size() == r.final_components.size() &&
         r.time_score_correlation > 0.0;
}

std::optional<std::size_t> time_coupled_robot(const Branch& b) {
  std::optional<std::size_t> found;
  std::size_t last = 0;
  for (std::size_t i = 0; i < b.robots.size(); ++i) {
    const RobotOutcome& r = b.robots[i];
    if (!r.finished || !same_time(r.finish_time_s, b.completion_time_s)) continue;
    ++last;
    if (has_time_scores(r)) found = i;
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

TimeScores time_scores_of(const RobotOutcome& r) {
  TimeScores s;
  s.scores = r.final_time_scores;
  for (std::size_t k = 0; k < r.final_components.size(); ++k) s.weights.push_back(component_weight(r, k));
  s.rho = r.time_score_correlation;
  return s;
}

std::vector<double> time_given_components(const TimeScores& s, double p_time) {
  const std::size_t n = s.scores.size();
  std::vector<double> given(n);
  double margin = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    given[k] = time_given_score(p_time, s.rho, s.scores[k]);
    margin += s.weights[k] * given[k];
  }
  for (double& g : given) g = margin > 0.0 ? std::min(1.0, g * p_time / margin) : p_time;
  return given;
}

BranchRadii::BranchRadii(const Branch& b, const mission::Mission& mission, const std::vector<double>& rmax) {
  const std::optional<std::size_t> c = time_coupled_robot(b);
  if (c) coupled_ = time_scores_of(b.robots[*c]);
  for (const double r : rmax) {
    double others = 1.0;
    std::vector<double> parts;
    for (std::size_t i = 0; i < b.robots.size(); ++i) {
      const RobotOutcome& robot = b.robots[i];
      const Eigen::Vector2d goal(mission.robots[i].goal.x_m, mission.robots[i].goal.y_m);
      if (c && i == *c) {
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

std::vector<double> BranchRadii::joints(double p_time) const {
  std::vector<double> out;
  if (!coupled_ || !(p_time > 0.0) || !(p_time < 1.0)) {
    for (const double r : radius_) out.push_back(p_time * r);
    return out;
  }
  const std::vector<double> given = time_given_components(*coupled_, p_time);
  for (std::size_t j = 0; j < radius_.size(); ++j) {
    double joint = 0.0;
    for (std::size_t k = 0; k < given.size(); ++k) joint += given[k] * within_[j][k];
    joint *= others_[j];
    // Never past what the two curves allow (Frechet bounds).
    out.push_back(std::clamp(joint, std::max(0.0, p_time + radius_[j] - 1.0), std::min(p_time, radius_[j])));
  }
  return out;
}

}  // namespace p3at::verifier::engine
