#pragma once
/// The cross-check campaign (docs/crosscheck.md): for each mission, robot
/// models calibrated from its world alone (never from the mission's own
/// runs), `vipars verify` and `vipars validate` on one grid spanning where
/// the probabilities rise, and the scores (scoring.hpp). Every mission's
/// files land in a folder of its own, with the command that redoes it.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p3at/crosscheck/scoring.hpp"
#include "p3at/crosscheck/separation_curve.hpp"
#include "p3at/mission_gen/generator.hpp"

namespace p3at::crosscheck {

/// One mission to cross-check: its two files' text and where they came from.
struct MissionInput {
  std::string name;                      ///< unique in the campaign (folder name)
  std::string mission_yaml, world_yaml;
  std::optional<std::uint64_t> generator_seed;  ///< set for generated missions
  std::string source;                    ///< "generated --seed S" or the folder it was read from
  std::string models_yaml;               ///< non-empty: use these models instead of calibrating (--shipped-models)
  std::shared_ptr<const mission_gen::GeneratedMission> generated;  ///< generated missions: routes for the floor plan
};

/// Generated missions for seeds first..last (robots A:B).
std::vector<MissionInput> generated_inputs(std::uint64_t first, std::uint64_t last, std::size_t min_robots,
                                           std::size_t max_robots);
/// Missions from folders: a folder holding mission.yaml and world.yaml, or a
/// folder of such folders (one level). With `shipped_models`, a models.yaml
/// beside them is used instead of calibrating. Throws std::runtime_error
/// naming a folder without missions.
std::vector<MissionInput> folder_inputs(const std::vector<std::string>& folders, bool shipped_models);

struct CampaignOptions {
  std::uint64_t runs = 1000;             ///< validation runs per mission
  std::uint64_t seed = 1;                ///< campaign seed: validation seeds derive from it and the mission
  unsigned jobs = 0;                     ///< validation threads; 0 = all cores
  std::size_t tmax_points = 41, rmax_points = 31;   ///< at most this many values per axis
  std::size_t calibration_runs = 20;     ///< manoeuvre runs per robot (vipars calibrate --runs)
  std::size_t calibration_messages = 400;
  std::string out_dir;                   ///< per-mission folders out_dir/missions/NAME; "" = write nothing
  std::string gnuplot = "gnuplot";       ///< floor plans of generated missions ("" = none)
  std::string command_prefix = "vipars crosscheck";  ///< for the printed reproduce commands
  /// Take a mission's validation runs from its folder's runs.part when that
  /// file was made from the same mission and world bytes, validation seed,
  /// run count and timeout (the runs never depend on the verifier, so a
  /// verifier change is re-scored without re-simulating). Changes no result.
  bool reuse_runs = false;
  /// Calibrate nothing, verify nothing: only make (or keep) each mission's
  /// validation runs in its folder, for a later --reuse-runs campaign to
  /// score (a sweep's simulation started while the verifier still changes).
  bool runs_only = false;
};

/// The validation's per-run time budget: twice the criterion's Tmax, at least
/// 120 s. It depends on the mission alone, never on the verifier, so cached
/// runs stay valid while the verifier changes; the scored Tmax axis stops at it.
double validation_timeout_s(double tmax_s);

/// One robot's final distance to its goal, verify's prediction against the
/// runs' (`vipars verify --json`'s and `vipars validate --json`'s robots):
/// which robot a radius error comes from, and whether it is the distance's
/// level or its spread.
struct RobotDistance {
  std::string name;
  double verify_mean_m = 0.0, verify_sd_m = 0.0;
  double validate_mean_m = 0.0, validate_sd_m = 0.0;
  /// Both sides describe the same finished robot: verify has it finish with
  /// under 1 % blocked mass, under 1 % of the runs failed, and the runs'
  /// distance spreads (sd > 0). Only these enter the summary's ratios.
  bool comparable = false;
};

struct MissionResult {
  std::string name, source;
  std::optional<std::uint64_t> generator_seed;
  std::size_t robots = 0;
  std::string error;                     ///< non-empty: the mission could not be cross-checked (why)
  bool evaluable = true;                 ///< verify's JSON "evaluable" (absent = true)
  std::vector<std::string> approximations;   ///< verify's JSON "approximations", one line each
  std::string calibration_note;          ///< how the robots were calibrated
  std::uint64_t runs = 0, failed_runs = 0;
  bool runs_reused = false;              ///< the validation came from the folder's runs.part (--reuse-runs)
  bool runs_only = false;                ///< --runs-only: the runs were made or kept, nothing scored
  std::string tmax_range, rmax_range;    ///< the grid, A:B:STEP
  double criteria_tmax_s = 0.0, criteria_rmax_m = 0.0;
  double verify_p_joint = 0.0, validate_p_joint = 0.0;  ///< at the mission's own criteria
  bool verify_go = false;
  MissionScore score;
  /// The closest-approach curve (separation_curve.hpp); absent for one robot,
  /// or when no run's robots came within 3 m of each other.
  std::optional<SeparationScore> separation;
  std::vector<RobotDistance> robot_distances;  ///< per robot, in the mission's order (empty: not scored)
  double calibrate_s = 0.0, verify_s = 0.0, validate_s = 0.0;   ///< CPU-thread wall time of each step
  /// Scoring (the grids read again, the closest-approach curve): its own
  /// figure because a many-robot mission's separation curve once cost more
  /// than the rest of its cross-check together (docs/crosscheck.md).
  double score_s = 0.0;
  std::string folder;                    ///< where its files are ("" when not written)
  std::string reproduce;                 ///< one command that redoes this mission alone
};

/// Progress of one mission: a phase ("calibrating", "validating", ...) and,
/// while validating, runs done of total.
using MissionProgress = std::function<void(const std::string& phase, std::uint64_t done, std::uint64_t total)>;

/// Cross-checks one mission. Never throws for a bad mission: `error` says
/// what went wrong (a file that does not load, a calibration that fails).
MissionResult run_mission(const MissionInput& input, const CampaignOptions& options,
                          const MissionProgress& progress = {});

/// The validation seed of a mission: from the campaign seed and the mission's name.
std::uint64_t mission_validation_seed(std::uint64_t campaign_seed, const std::string& name);

}  // namespace p3at::crosscheck
