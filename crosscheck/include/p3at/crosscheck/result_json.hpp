#pragma once
/// The campaign's results for people (one line per mission, a summary table)
/// and for machines (JSON), and the summary's statistics.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p3at/crosscheck/campaign.hpp"
#include "p3at/crosscheck/scoring.hpp"

namespace p3at::crosscheck {

/// One error measure over the scored missions.
struct MetricStats {
  std::size_t missions = 0;
  double worst = 0.0, p50 = 0.0, p90 = 0.0, p95 = 0.0;   ///< nearest-rank percentiles
  std::size_t within = 0;                                ///< missions within the bound
};

struct CampaignSummary {
  std::size_t missions = 0;          ///< all, including those that could not run
  std::size_t scored = 0;            ///< cross-checked (evaluable or not)
  std::size_t could_not_run = 0;     ///< MissionResult::error set
  std::size_t not_evaluable = 0;     ///< scored, but verify said it cannot evaluate them
  MetricStats time_strict, time_tolerant, radius_strict, radius_tolerant, joint_strict, joint_tolerant;
  std::size_t all_within_strict = 0, all_within_tolerant = 0;
  std::size_t overconfident_cells = 0;       ///< over-confident GO cells on evaluable missions
  std::size_t overconfident_missions = 0;    ///< evaluable missions with at least one
  std::size_t overconfident_cells_not_evaluable = 0;  ///< the same on missions verify refused to vouch for
  std::uint64_t runs = 0;                    ///< validation runs in all
  /// The closest-approach curve, over the missions that have one.
  MetricStats separation_strict, separation_tolerant;
  std::size_t separation_overconfident_points = 0, separation_overconfident_missions = 0;
  /// Each comparable robot's final distance (campaign.hpp, RobotDistance):
  /// the ratio of verify's spread to the runs', by nearest rank, how many are
  /// under 2/3 (too narrow: the side a wrong GO comes from) and over 3/2, and
  /// |verify's mean - the runs'| (m).
  struct RobotDistances {
    std::size_t robots = 0;
    double sd_ratio_p10 = 0.0, sd_ratio_p50 = 0.0, sd_ratio_p90 = 0.0;
    std::size_t narrower = 0, wider = 0;
    double mean_error_p50_m = 0.0, mean_error_p90_m = 0.0, mean_error_worst_m = 0.0;
  } robot_distances;
};

CampaignSummary summarize(const std::vector<MissionResult>& results, const Bounds& bounds);

nlohmann::ordered_json mission_result_json(const MissionResult& result);
nlohmann::ordered_json summary_json(const CampaignSummary& summary, const Bounds& bounds);
/// Reads back what mission_result_json() wrote (missions.jsonl, score.json).
/// Throws nlohmann::json::exception for a document of another shape.
MissionResult mission_result_from_json(const nlohmann::json& j);

/// "gen_17  3 robots  time 0.032 / 0.012  radius ...  joint ...  GO! 0  ok" (strict / tolerant).
std::string mission_line(const MissionResult& result, const Bounds& bounds);
/// The summary table: worst and percentiles of each error, fractions within the bounds, over-confident GO cells.
std::string summary_text(const CampaignSummary& summary, const Bounds& bounds);

}  // namespace p3at::crosscheck
