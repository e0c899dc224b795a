// The completion time and the final position of one branch, together
// (engine/time_position.hpp, issue 13 item 7): a hand-made branch whose exact
// joint is known, against BranchRadii's, and the copula's own properties.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "engine/time_position.hpp"
#include "p3at/verifier/mog.hpp"

namespace v = p3at::verifier;
using v::engine::BranchRadii;
using v::engine::time_given_score;

namespace {

p3at::mission::Mission one_robot_to(double x, double y) {
  p3at::mission::Mission m;
  p3at::mission::RobotSpec r;
  r.name = "robot1";
  r.goal = {x, y};
  m.robots.push_back(r);
  return m;
}

v::Gaussian2 at(double x, double y, double var) {
  v::Gaussian2 g;
  g.mean = Eigen::Vector2d(x, y);
  g.cov = Eigen::Matrix2d::Identity() * var;
  return g;
}

// The robot's last leg had two equally likely NOISE paths: one pushed toward
// the goal fires `d` seconds early and comes to rest on it, one pushed aside
// fires `d` late and rests 1 m off. The rest of the finish time, N(m, s^2),
// is the same for both. The completion time is then the mixture
// 1/2 N(m - d, s^2) + 1/2 N(m + d, s^2), and
//   P(t <= T and within 0.5 m) = 1/2 Phi((T - m + d) / s)  (only the early path is near).
v::Branch two_paths(double m, double d, double s, bool with_scores) {
  v::Branch b;
  b.completion_time_s.components = {{0.5, m - d, s * s}, {0.5, m + d, s * s}};
  v::RobotOutcome r;
  r.finish_time_s = b.completion_time_s;
  r.final_components = {at(0.0, 0.0, 1e-4), at(1.0, 0.0, 1e-4)};
  r.final_weights = {0.5, 0.5};
  r.final_position = at(0.5, 0.0, 0.25);
  if (with_scores) {
    r.final_time_scores = {-1.0, 1.0};
    r.time_score_correlation = d / std::sqrt(s * s + d * d);
  }
  b.robots.push_back(r);
  return b;
}

}  // namespace

TEST_CASE("a branch whose early path ends near: the joint follows the paths, not the independence product") {
  const double m = 10.0, d = 1.0, s = 0.5;
  const v::Branch b = two_paths(m, d, s, true);
  const p3at::mission::Mission mission = one_robot_to(0.0, 0.0);
  const BranchRadii radii(b, mission, {0.5, 5.0});
  CHECK(radii.radius(0) == doctest::Approx(0.5));
  CHECK(radii.radius(1) == doctest::Approx(1.0));
  double worst = 0.0, worst_independent = 0.0;
  for (double t = 8.0; t <= 12.0; t += 0.05) {
    const double p_time = b.completion_time_s.cdf(t);
    const double exact = 0.5 * v::normal_cdf((t - m + d) / s);
    const double joint = radii.joints(p_time)[0];
    worst = std::max(worst, std::abs(joint - exact));
    worst_independent = std::max(worst_independent, std::abs(p_time * 0.5 - exact));
    // Rmax past every path: the joint is the time curve itself.
    CHECK(radii.joints(p_time)[1] == doctest::Approx(p_time).epsilon(1e-12));
    // Never beyond what the two curves allow.
    CHECK(joint <= std::min(p_time, 0.5) + 1e-12);
    CHECK(joint >= std::max(0.0, p_time + 0.5 - 1.0) - 1e-12);
  }
  INFO("worst |joint - exact| " << worst << ", the independence product's " << worst_independent);
  // At T = m the copula is exact (P(t <= m) = 1/2: q = 0, and Phi(rho / sqrt(1 - rho^2)) = Phi(d / s)).
  CHECK(radii.joints(b.completion_time_s.cdf(m))[0] == doctest::Approx(0.5 * v::normal_cdf(d / s)).epsilon(1e-9));
  CHECK(worst_independent > 0.2);
  CHECK(worst < 0.03);
}

TEST_CASE("without time scores, or with two robots finishing as the completion, a branch stays independent") {
  const p3at::mission::Mission mission = one_robot_to(0.0, 0.0);
  const v::Branch plain = two_paths(10.0, 1.0, 0.5, false);
  const BranchRadii radii(plain, mission, {0.5});
  CHECK_FALSE(v::engine::time_coupled_robot(plain).has_value());
  CHECK(radii.joints(0.3)[0] == doctest::Approx(0.3 * 0.5).epsilon(1e-12));

  // Two robots whose finish is the completion: which one's paths the time
  // follows is not known.
  v::Branch two = two_paths(10.0, 1.0, 0.5, true);
  two.robots.push_back(two.robots.front());
  p3at::mission::Mission both = mission;
  both.robots.push_back(mission.robots.front());
  CHECK_FALSE(v::engine::time_coupled_robot(two).has_value());
  const BranchRadii radii2(two, both, {0.5});
  CHECK(radii2.joints(0.3)[0] == doctest::Approx(0.3 * 0.25).epsilon(1e-12));

  // A teammate that finished earlier: the last one is coupled, the other's
  // position stays independent (its factor multiplies).
  v::Branch early = two_paths(10.0, 1.0, 0.5, true);
  v::RobotOutcome first = early.robots.front();
  first.finish_time_s = v::Mixture1::gaussian(3.0, 0.1);
  first.final_time_scores.clear();
  first.time_score_correlation = 0.0;
  early.robots.push_back(first);
  REQUIRE(v::engine::time_coupled_robot(early) == std::optional<std::size_t>(0));
  const BranchRadii radii3(early, both, {0.5});
  const BranchRadii alone(two_paths(10.0, 1.0, 0.5, true), mission, {0.5});
  CHECK(radii3.joints(0.5)[0] == doctest::Approx(alone.joints(0.5)[0] * 0.5).epsilon(1e-12));
}

TEST_CASE("the copula's conditional time: its margin, its ends and its direction") {
  // Over a standard normal score it averages back to P(t <= T).
  for (const double p : {0.01, 0.3, 0.5, 0.9}) {
    for (const double rho : {0.2, 0.7, 0.95}) {
      double sum = 0.0;
      const int n = 4000;
      for (int i = 0; i < n; ++i) {
        const double z = v::normal_quantile((i + 0.5) / n);
        sum += time_given_score(p, rho, z) / n;
      }
      CHECK(sum == doctest::Approx(p).epsilon(1e-3));
    }
  }
  CHECK(time_given_score(0.0, 0.9, -2.0) == 0.0);
  CHECK(time_given_score(1.0, 0.9, 2.0) == 1.0);
  CHECK(time_given_score(0.4, 0.0, 3.0) == 0.4);
  // An early path (negative score) has finished more often by T than a late one.
  CHECK(time_given_score(0.4, 0.8, -1.0) > 0.4);
  CHECK(time_given_score(0.4, 0.8, 1.0) < 0.4);
}
