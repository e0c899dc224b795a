#pragma once
// `vipars calibrate --hal URL`: the manoeuvres on one robot over ARCOS
// (p3at_sim, MobileSim or a real Pioneer), in real (or p3at_sim's paced) time.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/calibration_rig/calibrate_drive.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::vipars {

/// Connects to `url` (tcp://HOST:PORT or serial:///dev/...), drives `plan`
/// and appends the manoeuvres of `robot` to `out`. True poses come from
/// `truth_csv` (a file p3at_sim --truth-csv is writing) at each manoeuvre's
/// ends; with an empty `truth_csv` there are none (a lab measures them and
/// types them into the log). Throws DriveError or std::runtime_error.
void drive_over_arcos(const std::string& url, const std::string& robot, const ManoeuvrePlan& plan,
                      const std::string& truth_csv, std::vector<verifier::Manoeuvre>& out);

/// The latest row of `robot` in a p3at_sim truth CSV (docs/simulator.md), if any.
/// Throws std::runtime_error for a file that cannot be read or is not one.
std::optional<verifier::TruePose> latest_truth(const std::string& truth_csv, const std::string& robot);

}  // namespace p3at::vipars
