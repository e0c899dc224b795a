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

  /// Gaussian with mean 0 and standard deviation `sd` (0 → always 0, and no draw
  /// is consumed), by Marsaglia's polar method. The radio and the CAN devices
  /// draw with it, and their tests pin its stream down.
  double gaussian(double sd);

  /// Gaussian with mean 0 and standard deviation `sd` (0 → always 0, and no
  /// draw is consumed), by the ziggurat method: 98.5 % of the time one engine
  /// draw, two table look-ups and a multiplication, no logarithm; several
  /// times faster than gaussian(). The robots' physics (odometry errors, sonar
  /// noise) draws with it, dozens of times per simulated cycle. Same
  /// distribution as gaussian(), other numbers from the same seed.
  double normal(double sd);

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace p3at::sim
