#pragma once
// The validation document (`vipars validate --json`, docs/validation.md): one
// builder shared by `vipars validate` and `vipars report`, so the report's
// validation.json is exactly what the stand-alone command prints.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "p3at/team_sim/empirical.hpp"

namespace p3at::vipars {

struct ValidationSummary {
  std::string mission_name;
  double threshold = 0.0;
  const team_sim::EmpiricalPoint* point = nullptr;  ///< required
  const team_sim::EmpiricalGrid* grid = nullptr;    ///< optional: no `grid` key without it
  double region_low = 0.05, region_high = 0.95;     ///< the grid's region thresholds
  std::uint64_t seed = 1;
  std::string world_file, mission_file;
};

/// Keys in the documented order: those of `vipars verify --json`, plus runs,
/// failed_runs and a _ci_low / _ci_high pair beside each probability.
nlohmann::ordered_json validation_json(const ValidationSummary& summary);

}  // namespace p3at::vipars
