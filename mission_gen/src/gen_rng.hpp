#pragma once
// The generator's random stream: SplitMix64 and our own transforms, so a seed
// gives the same mission with any compiler and standard library.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace p3at::mission_gen {

class GenRng {
 public:
  explicit GenRng(std::uint64_t seed) : state_(seed ^ 0x5DEECE66DULL) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// log-uniform in [lo, hi], lo > 0: as many short values as long ones per octave.
  double log_uniform(double lo, double hi) { return lo * std::exp(unit() * std::log(hi / lo)); }
  /// Integer in [lo, hi].
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    return lo + static_cast<std::int64_t>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool chance(double p) { return unit() < p; }
  /// Index drawn with the given (unnormalised) weights.
  std::size_t weighted(std::initializer_list<double> weights) {
    double total = 0.0;
    for (double w : weights) total += w;
    double x = unit() * total;
    std::size_t i = 0;
    for (double w : weights) {
      if (x < w) return i;
      x -= w;
      ++i;
    }
    return weights.size() - 1;
  }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(next() % v.size())];
  }

 private:
  std::uint64_t state_;
};

/// Rounded to `step` (people write 0.35, not 0.3471).
inline double round_to(double x, double step) { return std::round(x / step) * step; }

}  // namespace p3at::mission_gen
