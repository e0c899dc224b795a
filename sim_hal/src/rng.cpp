#include "p3at/sim/rng.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace p3at::sim {

namespace {

// splitmix64: spreads (seed, stream) over the whole 64-bit state so that
// neighbouring seeds and streams give unrelated sequences.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The ziggurat (Marsaglia and Tsang, "The Ziggurat Method for Generating
// Random Variables", 2000) for the half density f(x) = exp(-x²/2), x >= 0,
// cut into 256 layers of equal area v. Layer 0 is the base: the rectangle
// [0, r] × [0, f(r)] plus the tail beyond r, drawn as a rectangle of width
// x[0] = v / f(r). Layer i >= 1 is the rectangle [0, x[i]] × [f(x[i]), f(x[i+1])],
// with x[256] = 0. A point drawn uniformly in a layer whose abscissa is below
// x[i+1] lies under the curve whatever its height: that is the fast path.
// The tables come from exp, log, sqrt and erfc once, at first use.
constexpr std::size_t kLayers = 256;
constexpr double kTailStart = 3.6541528853610088;  // r for 256 layers: the chain below closes at x[256] = 0

double half_density(double x) { return std::exp(-0.5 * x * x); }

struct ZigguratTables {
  std::array<double, kLayers + 1> x{};  // layer widths, decreasing; x[256] = 0
  std::array<double, kLayers + 1> f{};  // f(x[i]) for i >= 1 (f[256] = 1); f[0] is unused

  ZigguratTables() {
    // Each layer's area: the base rectangle plus the tail's integral.
    const double area = kTailStart * half_density(kTailStart) +
                        std::sqrt(std::numbers::pi / 2.0) * std::erfc(kTailStart / std::numbers::sqrt2);
    x[0] = area / half_density(kTailStart);
    x[1] = kTailStart;
    for (std::size_t i = 1; i + 1 < kLayers; ++i) {
      x[i + 1] = std::sqrt(-2.0 * std::log(half_density(x[i]) + area / x[i]));
    }
    x[kLayers] = 0.0;
    for (std::size_t i = 0; i <= kLayers; ++i) f[i] = half_density(x[i]);
  }
};

const ZigguratTables& ziggurat() {
  static const ZigguratTables tables;
  return tables;
}

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream) : engine_(mix(mix(seed) ^ mix(stream + 0x632BE59BD9B4E019ull))) {}

double Rng::uniform() {
  // The top 53 bits make an exactly representable double in [0, 1).
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double Rng::gaussian(double sd) {
  if (sd == 0.0) return 0.0;
  if (has_spare_) {
    has_spare_ = false;
    return spare_ * sd;
  }
  // Marsaglia's polar method: two independent standard normals per accepted pair.
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor * sd;
}

double Rng::normal(double sd) {
  if (sd == 0.0) return 0.0;
  const ZigguratTables& z = ziggurat();
  for (;;) {
    // One draw gives the layer (bits 0-7), the sign (bit 8) and the abscissa
    // (the top 53 bits): disjoint bits, so independent.
    const std::uint64_t bits = engine_();
    const std::size_t layer = bits & 0xFFu;
    const double x = static_cast<double>(bits >> 11) * 0x1.0p-53 * z.x[layer];
    // The sign goes into the sign bit without a branch: a coin flip is the
    // one thing a branch predictor cannot learn.
    const auto with_sign = [bits](double magnitude) {
      return std::bit_cast<double>(std::bit_cast<std::uint64_t>(magnitude) ^ ((bits & 0x100u) << 55));
    };
    if (x < z.x[layer + 1]) return with_sign(x) * sd;  // wholly under the curve
    if (layer == 0) {
      // Beyond r (Marsaglia's tail method): r + e with e exponential of rate
      // r, accepted with probability exp(-e²/2).
      double e = 0.0;
      double y = 0.0;
      do {
        e = -std::log(1.0 - uniform()) / kTailStart;  // 1 - uniform() is in (0, 1]
        y = -std::log(1.0 - uniform());
      } while (y + y < e * e);
      return with_sign(kTailStart + e) * sd;
    }
    // The wedge between the curve and the layer's right edge: accept a height
    // drawn uniformly in the layer if it lies under the curve, else start over.
    const double height = z.f[layer] + uniform() * (z.f[layer + 1] - z.f[layer]);
    if (height < half_density(x)) return with_sign(x) * sd;
  }
}

}  // namespace p3at::sim
