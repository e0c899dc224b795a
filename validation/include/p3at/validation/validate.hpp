#pragma once
// `vipars validate`'s run (docs/validation.md): the validation campaign, N
// fast-time runs of the real executive against the simulated hardware on J
// threads, and the fraction that met the criteria, with 95 % Wilson intervals,
// printed as text or JSON, optionally one CSV row per run; or one shard of
// it, written as a part for `vipars merge` (docs/cluster.md).

#include <cstdint>
#include <string>

namespace p3at::vipars {

struct ValidateOptions {
  std::string mission_file;
  std::string world_file;
  std::uint64_t trials = 0;
  unsigned jobs = 0;  // 0: hardware concurrency
  std::uint64_t seed = 1;
  double tmax_s = 0.0;  // used when given (CLI::Option::count)
  double rmax_m = 0.0;
  bool tmax_given = false;
  bool rmax_given = false;
  std::string tmax_range;
  std::string rmax_range;
  double region_low = 0.05;
  double region_high = 0.95;
  double timeout_s = 900.0;
  bool json = false;
  std::string csv_file;
  std::string shard;      ///< "I/N": only shard I of N's runs, written as a part (docs/cluster.md)
  std::string part_file;  ///< where a shard writes its part
};

/// Runs the campaign and prints the report; returns the exit status
/// (p3at/common/vipars_exit.hpp).
int run_validate(ValidateOptions options);

}  // namespace p3at::vipars
