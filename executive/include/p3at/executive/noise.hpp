#pragma once
/// NOISE's random direction: a uniformly random unit vector in world (mission)
/// coordinates, held for `persistence` control cycles, then redrawn. Every draw
/// comes from one std::mt19937_64 per robot, seeded from (run seed, robot name),
/// so the same seed gives the same run on every platform (the angle is made from
/// the generator's raw bits, not from a library distribution whose algorithm
/// the standard leaves open).

#include <cstdint>
#include <random>
#include <string_view>

#include "p3at/executive/schemas.hpp"

namespace p3at::exec {

/// The noise generator's seed for one robot of a run: a SplitMix64 mix of
/// `run_seed` and the FNV-1a hash of `robot_name`. Pure; stable across platforms.
std::uint64_t noise_seed(std::uint64_t run_seed, std::string_view robot_name);

class NoiseSource {
 public:
  /// Seeds the generator with noise_seed(run_seed, robot_name).
  NoiseSource(std::uint64_t run_seed, std::string_view robot_name);

  /// Forgets the held direction: the next next() draws a new one. Called on
  /// entering a GoToGuarded state, so a state's first cycle has a fresh direction.
  void restart() { remaining_cycles_ = 0; }

  /// The direction for this control cycle (call once per cycle): redrawn when the
  /// previous one has been held `persistence_cycles` times (values below 1 count as 1).
  Vec2<double> next(std::int64_t persistence_cycles);

  /// How many directions have been drawn so far.
  std::uint64_t draws() const { return draws_; }

 private:
  std::mt19937_64 rng_;
  Vec2<double> direction_{1.0, 0.0};
  std::int64_t remaining_cycles_ = 0;
  std::uint64_t draws_ = 0;
};

}  // namespace p3at::exec
