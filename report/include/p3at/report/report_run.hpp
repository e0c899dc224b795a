#pragma once
// `vipars report MISSION --models ... --world ... --trials N`: runs the
// verification and the validation campaign in this process, through the same
// library calls as `vipars verify` and `vipars validate`, and returns their
// JSON documents (the keys of docs/verifier.md and docs/validation.md, plus
// a `command` key: the stand-alone command that gives the same document).

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/report/report_errors.hpp"

namespace p3at::vipars::report {

struct RunRequest {
  std::string mission_file, models_file, world_file;
  std::uint64_t trials = 0;
  unsigned jobs = 0;  ///< 0: every core
  std::uint64_t seed = 1;
  double timeout_s = 900.0;
  std::optional<double> tmax_s, rmax_m;
  std::string tmax_range, rmax_range;  ///< A:B:STEP, both required
  Thresholds thresholds;
};

struct RunOutput {
  nlohmann::ordered_json verification, validation;
  double verify_wall_s = 0.0, validate_wall_s = 0.0;
  unsigned jobs = 1;
};

/// Errors: unreadable or invalid files or flags (file:line:column from the
/// loaders), a failed verification.
Result<RunOutput> run_verify_and_validate(const RunRequest& request,
                                          const std::function<void(const std::string&)>& progress);

}  // namespace p3at::vipars::report
