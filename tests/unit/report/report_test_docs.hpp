#pragma once
// Two small handwritten documents shaped like `vipars verify --json` and
// `vipars validate --json` output (docs/verifier.md, docs/validation.md) on
// a 3 x 2 grid, with differences chosen so that every error below is exact
// in binary (0.125, 0.09375, ...) and the answers can be written down.

#include <nlohmann/json.hpp>

namespace p3at::test {

// |verify − validate|:
//   P(t) curve over tmax 10, 20, 30:   0.0625, 0.125, 0       -> max 0.125 at 20 s (FAIL against 0.05)
//   P(r) curve over rmax 1, 1.5:       0, 5.55e-17            -> max at 1.5 m (PASS)
//   joint [tmax][rmax]:                [0, 0], [0.0125, 0], [0, 0.09375]
//                                       -> max 0.09375 at (30 s, 1.5 m) (FAIL against 0.08)
inline nlohmann::json verification_doc() {
  return nlohmann::json::parse(R"({
    "mission": "toy", "decision": "no-go", "tmax_s": 20, "rmax_m": 1.5, "threshold": 0.8,
    "p_time": 0.5, "p_radius": 0.30000000000000004, "p_joint": 0.125,
    "completion_mean_s": 21.0, "completion_sd_s": 3.0, "robots": [], "criteria": [], "failed": [],
    "pruned_mass": 0, "blocked_mass": 0, "branches": 1, "subsystems": 4,
    "grid": {
      "tmax": [10, 20, 30], "rmax": [1, 1.5],
      "p_time": [0.0625, 0.5, 1],
      "p_radius": [0.1, 0.30000000000000004],
      "p_joint": [[0, 0.01], [0.05, 0.125], [0.1, 0.96875]],
      "region": [["unsuccessful", "unsuccessful"], ["uncertain", "uncertain"], ["uncertain", "successful"]]
    }
  })");
}

inline nlohmann::json validation_doc() {
  return nlohmann::json::parse(R"({
    "mission": "toy", "tmax_s": 20, "rmax_m": 1.5, "threshold": 0.8,
    "p_time": 0.375, "p_time_ci_low": 0.25, "p_time_ci_high": 0.5,
    "p_radius": 0.3, "p_radius_ci_low": 0.2, "p_radius_ci_high": 0.4,
    "p_joint": 0.125, "p_joint_ci_low": 0.0625, "p_joint_ci_high": 0.1875,
    "runs": 64, "failed_runs": 2, "robots": [], "completion_mean_s": 22.5, "completion_sd_s": 2.5,
    "grid": {
      "tmax": [10, 20, 30], "rmax": [1, 1.5],
      "p_time": [0, 0.375, 1], "p_radius": [0.1, 0.3],
      "p_joint": [[0, 0.01], [0.0375, 0.125], [0.1, 0.875]],
      "region": [["unsuccessful", "unsuccessful"], ["unsuccessful", "uncertain"], ["uncertain", "uncertain"]],
      "p_time_ci_low": [0, 0.25, 0.9], "p_time_ci_high": [0.05, 0.5, 1],
      "p_radius_ci_low": [0.05, 0.2], "p_radius_ci_high": [0.2, 0.4],
      "p_joint_ci_low": [[0, 0], [0.01, 0.0625], [0.05, 0.8]],
      "p_joint_ci_high": [[0.05, 0.06], [0.1, 0.1875], [0.2, 0.95]]
    },
    "seed": 7, "world": "world.yaml", "mission_file": "mission.yaml"
  })");
}

}  // namespace p3at::test
