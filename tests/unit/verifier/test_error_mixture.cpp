// engine/error_mixture: the between-path part of the true-pose error kept as
// a small Gaussian mixture. Every operation keeps the moments it must (a
// merge may lose shape, never mass, mean or spread); a heading error moves
// the end of a later displacement the way a rotation about the start does.
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

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

namespace {

/// Two components 12 % / 88 % apart along the direction `deg` (weights as
/// gen_5157's robot1: the runs that turned the other way), centred.
ErrorMixture apart_along(double deg, double length_m) {
  const double a = deg * 3.14159265358979323846 / 180.0;
  const Eigen::Vector3d u(std::cos(a), std::sin(a), 0.0);
  return {{0.12, 0.88 * length_m * u, Eigen::Matrix3d::Zero()}, {0.88, -0.12 * length_m * u, Eigen::Matrix3d::Zero()}};
}

Eigen::Matrix2d rank_one(double deg, double var) {
  const double a = deg * 3.14159265358979323846 / 180.0;
  const Eigen::Vector2d u(std::cos(a), std::sin(a));
  return var * u * u.transpose();
}

double largest(const Eigen::Matrix2d& m) { return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues()(1); }

}  // namespace

TEST_CASE("aligned_to_total: a few degrees between two descriptions of one spread leave no residual") {
  // The components' spread along 58 degrees, the total's (propagated along
  // the paths) along 61.5 degrees and a little longer: total minus what the
  // components explain, floored, keeps a 5 cm sd across the spread that
  // would widen every component.
  const ErrorMixture m = apart_along(58.0, 0.7);
  const Eigen::Matrix2d total = rank_one(61.5, 0.0521) + 1e-6 * Eigen::Matrix2d::Identity();
  const double before = largest(floored_psd(total - explained_cov(m).topLeftCorner<2, 2>()));
  CHECK(std::sqrt(before) > 0.02);
  const ErrorMixture a = aligned_to_total(m, total);
  REQUIRE(a.size() == 2);
  CHECK(total_weight(a) == doctest::Approx(1.0));
  CHECK(mean_delta(a).norm() < 1e-12);
  // What is left is along the spread (the total is a little longer), not across it.
  const Eigen::Matrix2d left = floored_psd(total - explained_cov(a).topLeftCorner<2, 2>());
  const double across_deg = (61.5 + 90.0) * 3.14159265358979323846 / 180.0;
  const Eigen::Vector2d across(std::cos(across_deg), std::sin(across_deg));
  CHECK(std::sqrt(across.dot(left * across)) < 0.005);
  // Turned onto the total's axis: the far component now points along 61.5 degrees.
  CHECK(std::atan2(a[0].delta(1), a[0].delta(0)) * 180.0 / 3.14159265358979323846 == doctest::Approx(61.5).epsilon(1e-6));
  // Headings are left as they were.
  CHECK(a[0].delta(2) == m[0].delta(2));
}

TEST_CASE("aligned_to_total: never lengthens the spread, and leaves other shapes alone") {
  // Components explaining more than the total along the axis are shortened to it.
  const ErrorMixture m = apart_along(30.0, 0.8);
  const Eigen::Matrix2d small = rank_one(30.0, 0.02) + 1e-6 * Eigen::Matrix2d::Identity();
  const ErrorMixture s = aligned_to_total(m, small);
  CHECK(largest(explained_cov(s).topLeftCorner<2, 2>()) == doctest::Approx(largest(small)).epsilon(1e-3));
  // Axes 40 degrees apart: a different shape, not a disagreement. Unchanged.
  const Eigen::Matrix2d other = rank_one(70.0, 0.07);
  const ErrorMixture o = aligned_to_total(m, other);
  CHECK((o[0].delta - m[0].delta).norm() == 0.0);
  // Components that are most of nothing (a between spread under half the
  // total along its axis) are left too.
  const Eigen::Matrix2d wide = rank_one(30.0, 0.5);
  CHECK((aligned_to_total(m, wide)[0].delta - m[0].delta).norm() == 0.0);
  // One component, or none: nothing to align.
  CHECK(aligned_to_total(ErrorMixture{}, wide).empty());
}
