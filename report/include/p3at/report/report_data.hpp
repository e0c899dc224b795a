#pragma once
// `vipars report`'s inputs: the JSON documents of `vipars verify --json` and
// `vipars validate --json` (docs/verifier.md, docs/validation.md), read into
// one shape so the two can be compared cell by cell. Only the keys a report
// uses are read; the rest are ignored. Every structural problem comes back as
// an Error naming the file and the key (e.g. "grid.p_joint[3]: expected 41
// numbers, got 40"); a syntax error names file:line:column.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"

namespace p3at::vipars::report {

/// A 95 % interval per value of a curve (validation only).
struct Band {
  std::vector<double> low, high;
};

/// One side of the comparison: the verification or the validation.
/// One robot's figures as a document gives them (`robots`: verify's
/// predictions, validate's empirical ones); each absent when the document
/// (an older one) does not have it.
struct RobotSide {
  std::string name;
  std::optional<double> p_radius;                   ///< P(this robot within Rmax)
  std::optional<double> dist_mean_m, dist_sd_m;     ///< its true final distance to its goal
};

struct Side {
  std::string source;  ///< the file it came from (or a label), for messages
  std::string mission;
  double tmax_s = 0.0, rmax_m = 0.0, threshold = 0.0;  ///< the criterion point
  double p_time = 0.0, p_radius = 0.0, p_joint = 0.0;  ///< at the criterion point
  /// At the criterion point, validation only: [low, high] of p_time, p_radius, p_joint.
  std::optional<std::vector<double>> point_ci_low, point_ci_high;
  std::optional<std::uint64_t> runs, failed_runs, seed;              ///< validation only
  std::optional<std::string> decision;                               ///< verification only ("go"/"no-go")
  std::optional<std::string> command;                                ///< the `command` key, when the document has one
  std::optional<std::string> mission_file, world_file, models_file;  ///< paths named in the document

  // The grid (required): axes, curves and the joint surface [tmax][rmax].
  std::vector<double> tmax, rmax;
  std::vector<double> p_time_curve;    ///< over tmax
  std::vector<double> p_radius_curve;  ///< over rmax
  std::vector<std::vector<double>> p_joint_grid;
  std::vector<std::vector<std::string>> region;    ///< as the document says, possibly empty
  std::optional<Band> p_time_band, p_radius_band;  ///< validation only
  std::optional<std::vector<std::vector<double>>> p_joint_ci_low, p_joint_ci_high;  ///< validation only
  std::vector<RobotSide> robots;  ///< per robot, in the mission's order (empty when the document has none)
};

/// Reads a document already parsed. `source` names it in messages.
Result<Side> side_from_json(const nlohmann::json& doc, const std::string& source);

/// Reads and parses a file; a JSON syntax error names file:line:column.
Result<Side> load_side(const std::string& path);

/// The two sides must describe the same grid: the same axes (values equal
/// within 1e-9 relative), or the error says which axis differs and how.
Status check_same_grid(const Side& verification, const Side& validation);

/// The documents must be what they are passed as: a validation has `runs`
/// and confidence intervals, a verification has neither (a swapped pair of
/// files would otherwise give a plausible but meaningless report).
Status check_roles(const Side& verification, const Side& validation);

}  // namespace p3at::vipars::report
