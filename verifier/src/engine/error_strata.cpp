#include "engine/error_strata.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <Eigen/Eigenvalues>

#include "engine/noise_segments.hpp"
#include "engine/path_stepper.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {
namespace {

/// A shift of the leg below this anywhere along it cannot decide a contact
/// that the mean path does not already decide (the walls are checked at the
/// body's outline to the millimetre, but the odometry's own random error
/// spreads the runs by more than this within a leg).
constexpr double kMinShiftM = 0.02;
/// How far into the error's tail a wall is looked for (sd of the axis).
constexpr double kTailSds = 3.0;
/// Points along the leg at which the shift and the walls are measured.
constexpr int kLegPoints = 16;

// Slab edges on the positive side; the middle slab is |z| < 0.75.
constexpr double kEdges[] = {0.75, 1.5, 2.25};

std::array<ErrorStratum, kErrorStrata> make_strata() {
  std::array<ErrorStratum, kErrorStrata> out{};
  const double middle = normal_cdf(kEdges[0]) - normal_cdf(-kEdges[0]);
  out[0] = {0.0, middle};
  for (std::size_t k = 0; k < 3; ++k) {
    const double lo = kEdges[k];
    const bool last = k + 1 == 3;  // the tail beyond the last edge
    const double w = (last ? 1.0 : normal_cdf(kEdges[k + 1])) - normal_cdf(lo);
    const double z = (normal_pdf(lo) - (last ? 0.0 : normal_pdf(kEdges[k + 1]))) / w;
    out[1 + 2 * k] = {z, w};
    out[2 + 2 * k] = {-z, w};
  }
  return out;
}

}  // namespace

const std::array<ErrorStratum, kErrorStrata>& error_strata() {
  static const std::array<ErrorStratum, kErrorStrata> strata = make_strata();
  return strata;
}

StratumSlab stratum_slab(std::size_t k) {
  if (k == 0) return {-kEdges[0], kEdges[0]};
  const std::size_t edge = (k - 1) / 2;  // strata 1, 2 share edge 0; 3, 4 edge 1; 5, 6 edge 2
  const double lo = kEdges[edge];
  const double hi = edge + 1 < std::size(kEdges) ? kEdges[edge + 1] : std::numeric_limits<double>::infinity();
  if (k % 2 == 1) return {lo, hi};  // odd strata are on the positive side (make_strata)
  return {-hi, -lo};
}

double strata_variance() {
  double c = 0.0;
  for (const ErrorStratum& s : error_strata()) c += s.weight * s.z * s.z;
  return c;
}

std::optional<Eigen::Vector3d> wall_sensitive_axis(const BaseState& start, const mission::GoToGuardedParams& go,
                                                   const ErrorState& error, const std::vector<Segment>& walls,
                                                   double reach_m) {
  if (walls.empty()) return std::nullopt;
  const double dx = go.goal.x_m - start.x_m, dy = go.goal.y_m - start.y_m;
  const double length = std::hypot(dx, dy);
  if (!(length > 1e-6)) return std::nullopt;
  const Eigen::Vector2d along(dx / length, dy / length), across(-along.y(), along.x());
  // The sideways shift at s metres along the leg of an error e is a(s).e.
  const auto a_at = [&](double s) { return Eigen::Vector3d(across.x(), across.y(), s); };
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int k = 0; k <= kLegPoints; ++k) {
    const Eigen::Vector3d a = a_at(length * k / kLegPoints);
    m += a * a.transpose() / (kLegPoints + 1);
  }
  // v = S u, with S the covariance's square root and u the top eigenvector
  // of S M S: the 1-sd error that shifts the leg the most on average.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> cov_eig(0.5 * (error.cov + error.cov.transpose()));
  const Eigen::Vector3d root = cov_eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d s_root = cov_eig.eigenvectors() * root.asDiagonal() * cov_eig.eigenvectors().transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> mode(s_root * m * s_root);
  const Eigen::Vector3d axis = s_root * mode.eigenvectors().col(2);
  // The leg moved by the error's mean (start shifted, turned about it).
  const double c = std::cos(error.mean(2)), sn = std::sin(error.mean(2));
  const Eigen::Vector2d turned(c * along.x() - sn * along.y(), sn * along.x() + c * along.y());
  const Eigen::Vector2d true_start(start.x_m + error.mean(0), start.y_m + error.mean(1));
  double largest = 0.0;
  bool near = false;
  for (int k = 0; k <= kLegPoints; ++k) {
    const double s = length * k / kLegPoints;
    const double shift = std::abs(a_at(s).dot(axis));
    largest = std::max(largest, shift);
    const Eigen::Vector2d p = true_start + s * turned;
    if (any_within(walls, p.x(), p.y(), reach_m + kTailSds * shift)) near = true;
  }
  if (!(largest >= kMinShiftM) || !near) return std::nullopt;
  return axis;
}

bool strata_may_differ(const PathStepper& stepper, const std::vector<Walker>& entries, const Eigen::Vector3d& axis,
                       std::size_t directions, std::size_t cap, std::size_t& cycles) {
  // A share stuck below this is the quadrature's remainder, not a pinned stratum.
  constexpr double kStuckTolerance = 1e-3;
  const double outer = error_strata()[kErrorStrata - 2].z;
  double stuck[3] = {0.0, 0.0, 0.0};
  const double shifts[3] = {0.0, outer, -outer};
  for (int k = 0; k < 3; ++k) {
    std::vector<Walker> shifted = entries;
    for (Walker& w : shifted) w.error.mean += shifts[k] * axis;
    const NoiseQuadrature held = noise_quadrature(stepper, shifted, 0, directions, directions, directions, cap);
    cycles += held.cycles_simulated;
    stuck[k] = held.stuck;
  }
  return std::abs(stuck[1] - stuck[0]) > kStuckTolerance || std::abs(stuck[2] - stuck[0]) > kStuckTolerance;
}

namespace {

/// What the strata carry between them leaves each one's covariance; it
/// stays positive semidefinite because axis axis^T <= cov (axis = S u,
/// |u| = 1) and the strata carry less than all of it.
Eigen::Matrix3d within_stratum(const Eigen::Matrix3d& cov, const Eigen::Vector3d& axis) {
  const Eigen::Matrix3d within = cov - strata_variance() * axis * axis.transpose();
  return 0.5 * (within + within.transpose());
}

}  // namespace

std::vector<Walker> shifted_along(const std::vector<Walker>& walkers, const Eigen::Vector3d& axis, double z) {
  std::vector<Walker> out = walkers;
  for (Walker& w : out) {
    w.error.mean += z * axis;
    w.error.cov = within_stratum(w.error.cov, axis);
    w.stratum = 0;
  }
  return out;
}

std::vector<Walker> split_into_strata(const std::vector<Walker>& walkers, const Eigen::Vector3d& axis) {
  std::vector<Walker> out;
  out.reserve(walkers.size() * kErrorStrata);
  for (const Walker& w : walkers) {
    const Eigen::Matrix3d within = within_stratum(w.error.cov, axis);
    for (std::size_t k = 0; k < kErrorStrata; ++k) {
      Walker s = w;
      s.error.mean += error_strata()[k].z * axis;
      s.error.cov = within;
      s.weight = w.weight * error_strata()[k].weight;
      s.stratum = static_cast<std::uint8_t>(k);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace p3at::verifier::engine
