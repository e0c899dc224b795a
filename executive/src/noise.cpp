#include "p3at/executive/noise.hpp"

#include <cmath>

namespace p3at::exec {

std::uint64_t noise_seed(std::uint64_t run_seed, std::string_view robot_name) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a 64
  for (const char ch : robot_name) {
    hash ^= std::uint64_t{static_cast<unsigned char>(ch)};
    hash *= 0x100000001b3ULL;
  }
  // SplitMix64 finaliser over the combination, so nearby seeds give unrelated streams.
  std::uint64_t z = run_seed + 0x9e3779b97f4a7c15ULL * (hash | 1U);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

NoiseSource::NoiseSource(std::uint64_t run_seed, std::string_view robot_name)
    : rng_(noise_seed(run_seed, robot_name)) {}

Vec2<double> NoiseSource::next(std::int64_t persistence_cycles) {
  if (remaining_cycles_ <= 0) {
    constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
    // 53 random bits → a uniform double in [0, 1), the same on every platform.
    const double unit = static_cast<double>(rng_() >> 11U) * 0x1.0p-53;
    const double angle_rad = kTwoPi * unit;
    direction_ = Vec2<double>{std::cos(angle_rad), std::sin(angle_rad)};
    remaining_cycles_ = persistence_cycles < 1 ? 1 : persistence_cycles;
    ++draws_;
  }
  --remaining_cycles_;
  return direction_;
}

}  // namespace p3at::exec
