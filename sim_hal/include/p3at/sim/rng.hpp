#pragma once
/// The simulator's random numbers: std::mt19937_64 (fully specified by the
/// standard) with our own uniform and Gaussian transforms, because the
/// standard library's distributions differ between implementations. The same
/// seed gives the same run with any compiler and standard library.

#include <cstdint>
#include <random>

namespace p3at::sim {

class Rng {
 public:
  /// Seeded from a (world seed, stream) pair, e.g. stream = robot index, so
  /// every robot gets its own independent, reproducible sequence.
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0);

  /// Uniform in [0, 1).
  double uniform();

  /// Gaussian with mean 0 and standard deviation `sd` (0 → always 0, and no draw is consumed).
  double gaussian(double sd);

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace p3at::sim
