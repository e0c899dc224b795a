#pragma once
// `vipars simulate`'s run: the whole team in fast time against simulated
// P3-ATs, N runs from seed S (run i uses seed S+i), one CSV row per run,
// and a summary as text or JSON.

#include <cstdint>
#include <string>

namespace p3at::vipars {

struct SimulateOptions {
  std::string mission_file;
  std::string world_file;
  std::uint64_t runs = 1;
  std::uint64_t seed = 1;
  std::string csv_file;
  bool json = false;
  bool verbose = false;
  double timeout_s = 900.0;
};

/// Runs and prints; returns the exit status (p3at/common/vipars_exit.hpp).
int run_simulate(const SimulateOptions& options);

}  // namespace p3at::vipars
