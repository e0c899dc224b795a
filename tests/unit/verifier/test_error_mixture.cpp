// engine/error_mixture: the between-path part of the true-pose error kept as
// a small Gaussian mixture. Every operation keeps the moments it must (a
// merge may lose shape, never mass, mean or spread); a heading error moves
// the end of a later displacement the way a rotation about the start does.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/error_mixture.hpp"

using namespace p3at::verifier::engine;

namespace {

double total_weight(const ErrorMixture& m) {
  double w = 0.0;
  for (const ErrorComponent& c : m) w += c.weight;
  return w;
}

Eigen::Vector3d mean_delta(const ErrorMixture& m) {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (const ErrorComponent& c : m) d += c.weight * c.delta;
  return d;
}

ErrorMixture two_sided(double lateral_m, double heading_rad) {
  return {{0.5, Eigen::Vector3d(lateral_m, 0.0, heading_rad), Eigen::Matrix3d::Zero()},
          {0.5, Eigen::Vector3d(-lateral_m, 0.0, -heading_rad), Eigen::Matrix3d::Zero()}};
}

}  // namespace

TEST_CASE("reduce: at most the budget, weights 1, centred, the explained covariance unchanged") {
  ErrorMixture m;
  for (int k = 0; k < 40; ++k) {
    const double a = 0.157 * k;
    m.push_back({1.0 / 40.0, Eigen::Vector3d(0.3 * std::cos(a), 0.1 * std::sin(3 * a), 0.01 * (k % 2 ? 1 : -1)),
                 Eigen::Matrix3d::Zero()});
  }
  const Eigen::Vector3d centre = mean_delta(m);
  for (ErrorComponent& c : m) c.delta -= centre;  // deviations from a mean, as the engine makes them
  const Eigen::Matrix3d before = explained_cov(m);
  reduce(m, kMaxErrorComponents);
  REQUIRE(m.size() <= kMaxErrorComponents);
  CHECK(total_weight(m) == doctest::Approx(1.0));
  CHECK(mean_delta(m).norm() < 1e-12);
  CHECK((explained_cov(m) - before).norm() < 1e-12);  // merges keep the moments
}

TEST_CASE("reduce keeps a two-sided error two-sided, and merges what is the same") {
  ErrorMixture m = two_sided(0.44, 0.064);
  reduce(m, kMaxErrorComponents);
  REQUIRE(m.size() == 2);
  CHECK(std::abs(m[0].delta.x()) == doctest::Approx(0.44));
  // Identical deviations (perfect odometry) are one component, i.e. none kept apart.
  ErrorMixture same(8, ErrorComponent{0.125, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()});
  reduce(same, kMaxErrorComponents);
  CHECK(same.empty());
}

TEST_CASE("transport: a heading error turns the later displacement about the start") {
  ErrorMixture m{{1.0, Eigen::Vector3d(0.0, 0.0, 0.02), Eigen::Matrix3d::Zero()}};
  transport(m, 5.0, 0.0);  // 5 m along +x: the end moves 0.02 * 5 = 0.1 m to +y
  CHECK(m[0].delta.x() == doctest::Approx(0.0));
  CHECK(m[0].delta.y() == doctest::Approx(0.1));
  CHECK(m[0].delta.z() == doctest::Approx(0.02));
}

TEST_CASE("convolve: independent deviations add, so their covariances add") {
  const ErrorMixture a = two_sided(0.4, 0.0);
  const ErrorMixture b = two_sided(0.0, 0.05);
  const ErrorMixture c = convolve(a, b, kMaxErrorComponents);
  CHECK(c.size() == 4);
  CHECK((explained_cov(c) - explained_cov(a) - explained_cov(b)).norm() < 1e-12);
  // With one side empty the other is returned (reduced).
  CHECK(convolve({}, a, kMaxErrorComponents).size() == 2);
}

TEST_CASE("blend_branches: two branches' mixtures about their merged mean") {
  const ErrorMixture a = two_sided(0.2, 0.0), b = two_sided(0.2, 0.0);
  const Eigen::Vector3d ma(1.0, 0.0, 0.0), mb(-1.0, 0.0, 0.0);
  const ErrorMixture m = blend_branches(a, ma, 1.0, b, mb, 3.0, 8);
  CHECK(total_weight(m) == doctest::Approx(1.0));
  CHECK(mean_delta(m).norm() < 1e-12);
  // Between-branch spread: the means -0.5 apart from the merged mean -0.5
  // (0.25 * 1.5^2 + 0.75 * 0.5^2 = 0.75) plus each side's 0.04.
  CHECK(explained_cov(m)(0, 0) == doctest::Approx(0.75 + 0.04));
}

TEST_CASE("floored_psd: total less what the components explain, never negative") {
  Eigen::Matrix3d total = Eigen::Matrix3d::Identity() * 0.01;
  const ErrorMixture m = two_sided(0.05, 0.0);
  const Eigen::Matrix2d c = floored_psd((total - explained_cov(m)).topLeftCorner<2, 2>());
  CHECK(c(0, 0) == doctest::Approx(0.01 - 0.0025));
  CHECK(c(1, 1) == doctest::Approx(0.01));
  const Eigen::Matrix2d floored = floored_psd(-explained_cov(m).topLeftCorner<2, 2>());
  CHECK(floored.minCoeff() >= -1e-15);
}
