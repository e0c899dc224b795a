#include "p3at/sim/rng.hpp"

#include <cmath>

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

}  // namespace p3at::sim
