#include "p3at/team_sim/run_seed.hpp"

namespace p3at::team_sim {

std::uint64_t run_seed(std::uint64_t campaign_seed, std::uint64_t run_index) {
  // SplitMix64: state advances by the golden-ratio gamma, output is mixed.
  std::uint64_t z = campaign_seed + (run_index + 1) * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace p3at::team_sim
