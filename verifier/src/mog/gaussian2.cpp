// Probabilities of a 2-D Gaussian position falling in a disk (criteria on
// final positions, on robots keeping apart). Deterministic quadrature: in the
// covariance's principal axes the coordinates are independent, so the
// probability along the major axis is a difference of normal CDFs over the
// disk's chord, and only the minor axis is integrated numerically.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {
namespace {

// Further than this many standard deviations the mass is below 2e-22.
constexpr double kTailSigmas = 10.0;
// A minor axis below this share of the problem's size is taken as a line:
// the probability moves by at most about sqrt(1e-14) = 1e-7 by it.
constexpr double kLineRatio = 1e-14;
// Absolute error aimed for per panel of the adaptive quadrature.
constexpr double kPanelTolerance = 1e-11;
constexpr int kMaxDepth = 30;
constexpr int kMaxPanels = 64;
// Intervals one probability may evaluate at the most (15 integrand values
// each): a bound on the launch gate's time whatever the Gaussian. Smooth
// integrands need a few dozen.
constexpr int kMaxIntervals = 1 << 14;

// Gauss-Kronrod 15-point rule on [-1, 1] (with its embedded 7-point Gauss
// rule), nodes from the outside in; the last node is 0.
constexpr std::array<double, 8> kKronrodNodes = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// Gauss 7-point weights at Kronrod nodes 1, 3, 5 and 7 (the centre).
constexpr std::array<double, 4> kGaussWeights = {0.129484966168869693270611432679082,
                                                 0.279705391489276667901467771423780,
                                                 0.381830050505118944950369775488975,
                                                 0.417959183673469387755102040816327};

// P(-h <= N(a, s^2) <= h), s > 0, without cancelling two CDFs near 1.
double interval_probability(double a, double s, double h) {
  const double upper = (h - a) / s;
  const double lower = (-h - a) / s;
  if (lower > 0.0) return normal_cdf(-lower) - normal_cdf(-upper);
  return normal_cdf(upper) - normal_cdf(lower);
}

// The disk problem in principal axes: Z1 ~ N(a1, s1^2), Z2 ~ N(a2, s2^2)
// independent, P(Z1^2 + Z2^2 <= r^2). With z2 = r sin(t) the chord's
// half-length is r cos(t), smooth in t, so the rule sees no square-root edge.
struct DiskIntegrand {
  double a1, s1, a2, s2, r;
  double operator()(double t) const {
    const double z2 = r * std::sin(t);
    const double h = r * std::cos(t);
    if (!(h > 0.0)) return 0.0;
    return normal_pdf((z2 - a2) / s2) / s2 * h * interval_probability(a1, s1, h);
  }
};

struct Estimate {
  double kronrod;
  double gauss;
};

Estimate gauss_kronrod(const DiskIntegrand& f, double lo, double hi) {
  const double centre = 0.5 * (lo + hi);
  const double half = 0.5 * (hi - lo);
  const double fc = f(centre);
  double kronrod = kKronrodWeights[7] * fc;
  double gauss = kGaussWeights[3] * fc;
  for (std::size_t i = 0; i < 7; ++i) {
    const double dx = half * kKronrodNodes[i];
    const double pair = f(centre - dx) + f(centre + dx);
    kronrod += kKronrodWeights[i] * pair;
    if (i % 2 == 1) gauss += kGaussWeights[i / 2] * pair;
  }
  return Estimate{kronrod * half, gauss * half};
}

// Halves the interval until the 7- and 15-point rules agree to `tolerance`,
// or to what rounding lets them agree: a node of an interval of width w at t
// is placed to about eps |t|, which moves an integrand that varies over w by
// about eps |t| / w of its value. Below that floor the rules never agree, and
// halving down to kMaxDepth everywhere cost 2^kMaxDepth evaluations: a
// covariance of rank one by rounding (minor sd 1e-9 m, met on the CI gate's
// gen_8 during a verifier experiment) took 20 s for one probability. `intervals_left` bounds the work whatever happens.
double adaptive(const DiskIntegrand& f, double lo, double hi, double tolerance, int depth, int& intervals_left) {
  const Estimate e = gauss_kronrod(f, lo, hi);
  --intervals_left;
  const double width = hi - lo;
  const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * std::abs(e.kronrod) *
                          std::max(1.0, std::max(std::abs(lo), std::abs(hi)) / width);
  if (std::abs(e.kronrod - e.gauss) <= std::max(tolerance, rounding) || depth >= kMaxDepth || intervals_left < 2) {
    return e.kronrod;
  }
  const double mid = 0.5 * (lo + hi);
  const double left = adaptive(f, lo, mid, 0.5 * tolerance, depth + 1, intervals_left);
  return left + adaptive(f, mid, hi, 0.5 * tolerance, depth + 1, intervals_left);
}

}  // namespace

double probability_within(const Gaussian2& x, const Eigen::Vector2d& centre, double radius) {
  return probability_within(x, centre, radius, nullptr);
}

double probability_within(const Gaussian2& x, const Eigen::Vector2d& centre, double radius, int* intervals) {
  if (!(radius >= 0.0)) return 0.0;
  const Eigen::Vector2d mu = x.mean - centre;
  const double d = mu.norm();

  // Principal axes of the (symmetrised) covariance; a slightly negative
  // eigenvalue from rounding is a zero one.
  const double a = x.cov(0, 0);
  const double c = x.cov(1, 1);
  const double b = 0.5 * (x.cov(0, 1) + x.cov(1, 0));
  const double l1 = std::max(0.5 * (a + c) + std::hypot(0.5 * (a - c), b), 0.0);
  // det / l1 keeps the small eigenvalue accurate when the two differ a lot.
  const double l2 = l1 > 0.0 ? std::clamp((a * c - b * b) / l1, 0.0, l1) : 0.0;
  const double s1 = std::sqrt(l1);
  const double s2 = std::sqrt(l2);

  // Far outside or deep inside the disk, or a point.
  if (d - radius > kTailSigmas * s1) return 0.0;
  if (d + kTailSigmas * s1 < radius) return 1.0;
  if (!(s1 > 0.0)) return d <= radius ? 1.0 : 0.0;
  if (!(radius > 0.0)) return 0.0;  // a disk of radius 0 holds no mass of a spread distribution

  const double angle = 0.5 * std::atan2(2.0 * b, a - c);
  const Eigen::Vector2d major(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d minor(-major.y(), major.x());
  const double a1 = mu.dot(major);
  const double a2 = mu.dot(minor);

  if (s2 <= kLineRatio * (radius + d + s1)) {
    // All the mass on the line z2 = a2: the chord there, or nothing.
    if (std::abs(a2) >= radius) return 0.0;
    return std::clamp(interval_probability(a1, s1, std::sqrt(radius * radius - a2 * a2)), 0.0, 1.0);
  }

  // Integrate over z2 where its density is not negligible, in panels about
  // one minor standard deviation wide so that no peak falls between nodes.
  const double z_lo = std::max(-radius, a2 - kTailSigmas * s2);
  const double z_hi = std::min(radius, a2 + kTailSigmas * s2);
  if (!(z_lo < z_hi)) return 0.0;
  const int panels = std::clamp(static_cast<int>(std::ceil((z_hi - z_lo) / s2)), 1, kMaxPanels);
  const DiskIntegrand f{a1, s1, a2, s2, radius};
  const auto to_angle = [radius](double z) { return std::asin(std::clamp(z / radius, -1.0, 1.0)); };
  double total = 0.0;
  int intervals_left = kMaxIntervals;
  for (int i = 0; i < panels; ++i) {
    const double z0 = z_lo + (z_hi - z_lo) * static_cast<double>(i) / panels;
    const double z1 = i + 1 == panels ? z_hi : z_lo + (z_hi - z_lo) * static_cast<double>(i + 1) / panels;
    total += adaptive(f, to_angle(z0), to_angle(z1), kPanelTolerance, 0, intervals_left);
  }
  if (intervals != nullptr) *intervals += kMaxIntervals - intervals_left;
  return std::clamp(total, 0.0, 1.0);
}

double probability_apart(const Gaussian2& x, const Gaussian2& y, double distance) {
  const Gaussian2 difference{x.mean - y.mean, x.cov + y.cov};
  return std::clamp(1.0 - probability_within(difference, Eigen::Vector2d::Zero(), distance), 0.0, 1.0);
}

}  // namespace p3at::verifier
