#pragma once
/// The CI gate's baseline (docs/crosscheck.md, "The CI gate"): per mission,
/// the largest errors and over-confident GO cells allowed. Recorded from a
/// campaign with a margin; shipped examples are held to the bounds
/// (0.05 / 0.05 / 0.08) with the 1 % shift whatever they measured.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p3at/crosscheck/campaign.hpp"

namespace p3at::crosscheck {

struct BaselineEntry {
  std::string name;
  double time = 0.0, radius = 0.0, joint = 0.0;                       ///< strict limits
  double time_tolerant = 0.0, radius_tolerant = 0.0, joint_tolerant = 0.0;
  std::size_t overconfident_go_cells = 0;
};

/// Limits from measured results: measured + margin, capped at 1 (generated
/// missions); missions from folders (the shipped examples): the bounds with
/// the 1 % shift, max(bound, measured + margin) strictly, no over-confident GO.
std::vector<BaselineEntry> baseline_from(const std::vector<MissionResult>& results, const Bounds& bounds, double margin);
nlohmann::ordered_json baseline_json(const std::vector<BaselineEntry>& entries, const std::string& how_made);
/// Throws std::runtime_error naming the file and what is wrong.
std::vector<BaselineEntry> load_baseline(const std::string& path);

/// One line per violation ("gen_3: joint 0.112 > 0.095"); empty when every
/// mission is within its entry. A mission without an entry, or one that
/// could not run, is a violation.
std::vector<std::string> check_baseline(const std::vector<MissionResult>& results, const std::vector<BaselineEntry>& baseline);

}  // namespace p3at::crosscheck
