// run_mission(): calibrate from the world, validate, choose the grid, verify,
// score, and leave every file in the mission's folder (campaign.hpp).

#include "p3at/crosscheck/campaign.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "calibrate_world.hpp"
#include "p3at/common/log.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/crosscheck/grid_choice.hpp"
#include "p3at/crosscheck/result_json.hpp"
#include "p3at/mission_gen/generator.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/campaign_part.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/team_run.hpp"
#include "p3at/validation/validation_json.hpp"
#include "p3at/validation/verify_output.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::crosscheck {
namespace fs = std::filesystem;

std::uint64_t mission_validation_seed(std::uint64_t campaign_seed, const std::string& name) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a of the name, then mixed with the campaign seed
  for (char c : name) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return team_sim::run_seed(campaign_seed ^ h, 0);
}

std::vector<MissionInput> generated_inputs(std::uint64_t first, std::uint64_t last, std::size_t min_robots,
                                           std::size_t max_robots) {
  std::vector<MissionInput> out;
  for (std::uint64_t s = first; s <= last; ++s) {
    mission_gen::GenerateOptions o;
    o.seed = s;
    o.min_robots = min_robots;
    o.max_robots = max_robots;
    const mission_gen::GeneratedMission g = mission_gen::generate(o);
    MissionInput in;
    in.name = g.name;
    in.mission_yaml = g.mission_yaml;
    in.world_yaml = g.world_yaml;
    in.generator_seed = s;
    in.generated = std::make_shared<const mission_gen::GeneratedMission>(g);
    in.source = "--seeds " + std::to_string(s) + ":" + std::to_string(s) + " --robots " + std::to_string(min_robots) +
                ":" + std::to_string(max_robots);
    out.push_back(std::move(in));
    if (s == last) break;  // last may be the largest seed
  }
  return out;
}

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

bool is_mission_folder(const fs::path& p) {
  return fs::is_regular_file(p / "mission.yaml") && fs::is_regular_file(p / "world.yaml");
}

MissionInput folder_input(const fs::path& dir, bool shipped_models) {
  MissionInput in;
  in.name = dir.filename().string();
  if (in.name.empty() || in.name == ".") in.name = fs::absolute(dir).lexically_normal().filename().string();
  in.mission_yaml = read_text(dir / "mission.yaml");
  in.world_yaml = read_text(dir / "world.yaml");
  in.source = dir.string();
  if (shipped_models && fs::is_regular_file(dir / "models.yaml")) in.models_yaml = read_text(dir / "models.yaml");
  return in;
}

// The validation at each axis value, and shifted by -1 % and +1 %.
std::vector<ValidationPoint> curve_points(const std::vector<team_sim::Estimate>& mid,
                                          const std::vector<team_sim::Estimate>& lo,
                                          const std::vector<team_sim::Estimate>& hi) {
  std::vector<ValidationPoint> out;
  for (std::size_t i = 0; i < mid.size(); ++i) out.push_back({mid[i].p, mid[i].ci_low, mid[i].ci_high, lo[i].p, hi[i].p});
  return out;
}

std::vector<double> scaled(const std::vector<double>& axis, double f) {
  std::vector<double> out;
  for (double v : axis) out.push_back(v * f);
  return out;
}

// A run's largest final distance when it completed, +inf when it did not: a
// run cut off by its time budget (or aborted) has no final position, only the
// place where it stood when it was stopped.
/// Each robot's final distance on both sides (campaign.hpp, RobotDistance),
/// from verify's result and the validation document's robots.
std::vector<RobotDistance> robot_distances(const verifier::VerifyResult& verified, const nlohmann::ordered_json& validation,
                                           std::uint64_t runs, std::uint64_t failed_runs) {
  std::vector<RobotDistance> out;
  const bool runs_whole = runs > 0 && static_cast<double>(failed_runs) < 0.01 * static_cast<double>(runs);
  for (const verifier::RobotPrediction& p : verified.robots) {
    RobotDistance d;
    d.name = p.name;
    d.verify_mean_m = p.dist_mean_m;
    d.verify_sd_m = p.dist_sd_m;
    if (validation.contains("robots")) {
      for (const auto& w : validation["robots"]) {
        if (w.value("name", std::string()) != p.name) continue;
        d.validate_mean_m = w.value("dist_mean_m", 0.0);
        d.validate_sd_m = w.value("dist_sd_m", 0.0);
        d.comparable = p.finishes && p.p_blocked < 0.01 && runs_whole && d.validate_sd_m > 0.0;
      }
    }
    out.push_back(std::move(d));
  }
  return out;
}

double final_distance_m(const team_sim::RunResult& run) {
  return run.success() ? team_sim::worst_distance_m(run) : std::numeric_limits<double>::infinity();
}

// The validation's radius curve as the cross-check scores it: P(the run
// completed within its time budget and every robot ended within Rmax), at
// each Rmax and shifted by -1 % and +1 %. The verifier's side is its joint
// probability at Tmax = the budget. Both sides then speak of the same event:
// `vipars validate`'s own P(r) counts a timed-out run by where its robots
// stood when it was stopped (docs/validation.md), while the verifier has no
// time budget and counts a robot that never finishes as a failure, so on a
// mission no run completes the two read 1 and 0 of the same runs.
std::vector<ValidationPoint> completed_radius_curve(const std::vector<team_sim::RunResult>& runs,
                                                    const std::vector<double>& rmax, double budget_s) {
  const std::vector<double> at_budget{budget_s};
  const team_sim::EmpiricalGrid mid = team_sim::empirical_grid(runs, at_budget, rmax);
  const team_sim::EmpiricalGrid lo = team_sim::empirical_grid(runs, at_budget, scaled(rmax, 1 - kShiftFraction));
  const team_sim::EmpiricalGrid hi = team_sim::empirical_grid(runs, at_budget, scaled(rmax, 1 + kShiftFraction));
  return curve_points(mid.joint.front(), lo.joint.front(), hi.joint.front());
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The validation runs are kept beside the mission as a one-shard campaign
// part (the format `vipars validate --shard` writes, checksummed), whose
// header says what they were made from.
constexpr const char* kRunsFile = "runs.part";

team_sim::CampaignHeader runs_header(const MissionInput& input, const mission::Mission& mission, std::uint64_t seed,
                                     std::uint64_t runs, double timeout_s) {
  team_sim::CampaignHeader h;
  // BLAKE2b-256 over both files' bytes, each prefixed by its length so no two pairs collide by concatenation.
  h.content_hash = team_sim::part_checksum(std::to_string(input.mission_yaml.size()) + "\n" + input.mission_yaml +
                                           std::to_string(input.world_yaml.size()) + "\n" + input.world_yaml);
  h.seed = seed;
  h.trials = runs;
  h.timeout_s = timeout_s;
  h.tmax_s = mission.criteria.tmax_s;
  h.rmax_m = mission.criteria.rmax_m;
  h.tmax_axis = {h.tmax_s};
  h.rmax_axis = {h.rmax_m};
  h.mission_name = mission.name;
  h.threshold = mission.criteria.threshold;
  for (const mission::RobotSpec& r : mission.robots) h.robots.push_back(r.name);
  h.mission_file = "mission.yaml";
  h.world_file = "world.yaml";
  return h;
}

// The cached runs when the folder's file holds exactly this validation; a
// missing, damaged or different file is simply not used (and says why).
std::optional<std::vector<team_sim::RunResult>> cached_runs(const fs::path& file, const team_sim::CampaignHeader& want) {
  if (!fs::is_regular_file(file)) return std::nullopt;
  Result<team_sim::CampaignPart> part = team_sim::read_part_file(file.string());
  if (!part) {
    log::warn("crosscheck", "not reusing " + file.string() + ": " + part.error().message);
    return std::nullopt;
  }
  if (auto diff = team_sim::campaign_difference(part->header, want)) {
    log::info("crosscheck", "not reusing " + file.string() + ": made with another " + *diff);
    return std::nullopt;
  }
  if (part->shard.count != 1 || part->runs.size() != want.trials) return std::nullopt;
  return std::move(part->runs);
}

}  // namespace

std::vector<MissionInput> folder_inputs(const std::vector<std::string>& folders, bool shipped_models) {
  std::vector<MissionInput> out;
  for (const std::string& f : folders) {
    const fs::path dir(f);
    if (is_mission_folder(dir)) {
      out.push_back(folder_input(dir, shipped_models));
      continue;
    }
    if (!fs::is_directory(dir)) throw std::runtime_error(f + ": not a folder");
    std::vector<fs::path> subs;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
      if (e.is_directory() && is_mission_folder(e.path())) subs.push_back(e.path());
    }
    std::sort(subs.begin(), subs.end());
    if (subs.empty()) throw std::runtime_error(f + ": no mission.yaml and world.yaml in it or in its folders");
    for (const fs::path& p : subs) out.push_back(folder_input(p, shipped_models));
  }
  return out;
}

// The mission's validation runs (team_sim::run_campaign), quietly.
template <class Say>
std::vector<team_sim::RunResult> make_runs(const mission::Mission& mission, const sim::WorldConfig& world,
                                           const CampaignOptions& o, std::uint64_t vseed, double timeout_s, const Say& say) {
  team_sim::TeamScenario scenario(mission, world);
  team_sim::CampaignOptions co;
  co.runs = o.runs;
  co.seed = vseed;
  co.jobs = o.jobs;
  co.run.timeout_s = timeout_s;
  say("validating", 0, o.runs);
  // The executives' warnings (a Spin faster than the robot turns, once per
  // run) would fill stderr with thousands of copies; the runs' outcomes say it all.
  const log::Level level = log::threshold();
  log::threshold() = log::Level::error;
  std::vector<team_sim::RunResult> runs;
  try {
    runs = team_sim::run_campaign(scenario, co, [&](std::uint64_t done, std::uint64_t total) { say("validating", done, total); });
  } catch (...) {
    log::threshold() = level;
    throw;
  }
  log::threshold() = level;
  return runs;
}

MissionResult run_mission(const MissionInput& input, const CampaignOptions& o, const MissionProgress& progress) {
  MissionResult r;
  r.name = input.name;
  r.runs_only = o.runs_only;
  r.source = input.source;
  r.generator_seed = input.generator_seed;
  const auto say = [&progress](const std::string& phase, std::uint64_t done = 0, std::uint64_t total = 0) {
    if (progress) progress(phase, done, total);
  };
  try {
    const fs::path folder = fs::path(o.out_dir) / "missions" / input.name;
    fs::create_directories(folder);
    r.folder = folder.string();
    write_text(folder / "mission.yaml", input.mission_yaml);
    write_text(folder / "world.yaml", input.world_yaml);
    const mission::Mission mission = mission::load_mission_file((folder / "mission.yaml").string());
    const sim::WorldConfig world = sim::load_world_file((folder / "world.yaml").string());
    r.robots = mission.robots.size();
    r.criteria_tmax_s = mission.criteria.tmax_s;
    r.criteria_rmax_m = mission.criteria.rmax_m;
    if (input.generated && !o.gnuplot.empty()) {
      // A floor plan beside the files; a missing gnuplot costs the picture, not the mission.
      (void)mission_gen::draw_picture(*input.generated, (folder / "plan").string(), o.gnuplot);
    }

    if (o.runs_only) {
      // Only the runs (step 3 below): nothing here depends on the verifier.
      say("validating", 0, o.runs);
      const double timeout_s = validation_timeout_s(mission.criteria.tmax_s);
      const std::uint64_t vseed = mission_validation_seed(o.seed, input.name);
      const auto t0 = std::chrono::steady_clock::now();
      const team_sim::CampaignHeader header = runs_header(input, mission, vseed, o.runs, timeout_s);
      r.runs_only = true;
      if (auto cached = cached_runs(folder / kRunsFile, header)) {
        r.runs = cached->size();
        r.runs_reused = true;
      } else {
        const std::vector<team_sim::RunResult> runs = make_runs(mission, world, o, vseed, timeout_s, say);
        r.runs = runs.size();
        const Status written = team_sim::write_part_file((folder / kRunsFile).string(), team_sim::make_part(header, {0, 1}, runs));
        if (!written) throw std::runtime_error("cannot keep the runs: " + written.error().message);
      }
      r.validate_s = seconds_since(t0);
      return r;
    }

    // 1. Robot models from the world alone.
    say("calibrating");
    auto t0 = std::chrono::steady_clock::now();
    std::string models_yaml = input.models_yaml;
    if (models_yaml.empty()) {
      const CalibratedModels cal = calibrate_from_world(mission, world, o.calibration_runs, o.calibration_messages,
                                                        world.seed.value_or(1));
      models_yaml = cal.models_yaml;
      r.calibration_note = cal.note;
      write_text(folder / "calibration.txt", cal.fit_report);
    } else {
      r.calibration_note = "the folder's own models.yaml (--shipped-models)";
      // Its walls_from names a file beside it: the world copied here is that file's content.
      const std::string marker = "walls_from:";
      const std::size_t at = models_yaml.find(marker);
      if (at != std::string::npos) {
        const std::size_t eol = models_yaml.find('\n', at);
        models_yaml.replace(at, eol - at, "walls_from: world.yaml");
      }
    }
    write_text(folder / "models.yaml", models_yaml);
    const verifier::Models models = verifier::load_models_file((folder / "models.yaml").string());
    r.calibrate_s = seconds_since(t0);

    // 2. The verifier's curves on a coarse grid, up to 4 Tmax and 4 Rmax (at
    // least 3 m): where they rise, and so how long a validation run may take.
    say("verifying");
    t0 = std::chrono::steady_clock::now();
    verifier::VerifyOptions coarse;
    const double t_far = std::max(4.0 * mission.criteria.tmax_s, 10.0);
    const double r_far = std::max(4.0 * mission.criteria.rmax_m, 3.0);
    for (int k = 1; k <= 240; ++k) coarse.tmax_grid.push_back(t_far * k / 240.0);
    for (int k = 1; k <= 240; ++k) coarse.rmax_grid.push_back(r_far * k / 240.0);
    // One evaluation of the mission, read on both grids (the sequence is the expensive part).
    Result<verifier::SystemOutcome> outcome = verifier::evaluate_system(mission, models);
    if (!outcome) throw std::runtime_error("verify: " + outcome.error().message);
    Result<verifier::VerifyResult> first = verifier::verify_outcome(mission, models, *outcome, coarse);
    if (!first) throw std::runtime_error("verify: " + first.error().message);
    const Rise vt = rise_of_curve(first->grid->tmax, first->grid->p_time);
    const Rise vr = rise_of_curve(first->grid->rmax, first->grid->p_radius);
    r.verify_s = seconds_since(t0);

    // 3. The validation runs (the grid is chosen afterwards: any grid costs
    // nothing once the runs are in), or the folder's cached ones.
    const double timeout_s = validation_timeout_s(mission.criteria.tmax_s);
    const std::uint64_t vseed = mission_validation_seed(o.seed, input.name);
    t0 = std::chrono::steady_clock::now();
    const team_sim::CampaignHeader header = runs_header(input, mission, vseed, o.runs, timeout_s);
    std::vector<team_sim::RunResult> runs;
    if (auto cached = o.reuse_runs ? cached_runs(folder / kRunsFile, header) : std::nullopt) {
      runs = std::move(*cached);
      r.runs_reused = true;
    } else {
      runs = make_runs(mission, world, o, vseed, timeout_s, say);
      const Status written = team_sim::write_part_file((folder / kRunsFile).string(), team_sim::make_part(header, {0, 1}, runs));
      if (!written) log::warn("crosscheck", "cannot keep the runs: " + written.error().message);
    }
    r.validate_s = seconds_since(t0);

    // 4. The grid: where either side's curves rise.
    t0 = std::chrono::steady_clock::now();
    std::vector<double> times, dists;
    for (const team_sim::RunResult& run : runs) {
      times.push_back(team_sim::completion_time_s(run));
      dists.push_back(final_distance_m(run));
    }
    const Rise wt = rise_of_sample(times), wr = rise_of_sample(dists);
    const auto span = [](const Rise& a, const Rise& b, double fallback_lo, double fallback_hi) {
      if (!a.found && !b.found) return std::pair{fallback_lo, fallback_hi};
      if (!a.found) return std::pair{b.lo, b.hi};
      if (!b.found) return std::pair{a.lo, a.hi};
      return std::pair{std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
    };
    const auto [tlo, thi_wanted] = span(vt, wt, 0.5 * mission.criteria.tmax_s, 1.5 * mission.criteria.tmax_s);
    // Past the runs' time budget the validation knows nothing: the axis stops there.
    const double thi = std::min(thi_wanted, timeout_s);
    const auto [rlo, rhi] = span(vr, wr, 0.5 * mission.criteria.rmax_m, 1.5 * mission.criteria.rmax_m);
    const Axis tax = nice_axis(tlo, thi, o.tmax_points, 0.1);
    const Axis rax = nice_axis(rlo, rhi, o.rmax_points, 0.01);
    r.tmax_range = tax.range();
    r.rmax_range = rax.range();

    // 5. Verify on the grid.
    verifier::VerifyOptions vo;
    vo.tmax_grid = tax.values;
    vo.rmax_grid = rax.values;
    Result<verifier::VerifyResult> verified = verifier::verify_outcome(mission, models, *outcome, vo);
    if (!verified) throw std::runtime_error("verify: " + verified.error().message);
    // Located as `vipars verify mission.yaml` (the folder's own command) locates them.
    verifier::locate_in_mission_file(*verified, input.mission_yaml, "mission.yaml");
    r.verify_s += seconds_since(t0);
    r.verify_p_joint = verified->p_joint;
    r.verify_go = verified->go;
    nlohmann::json vj = vipars::verify_json(mission, *verified);
    if (vj.contains("evaluable") && vj["evaluable"].is_boolean()) r.evaluable = vj["evaluable"].get<bool>();
    if (vj.contains("approximations") && vj["approximations"].is_array()) {
      for (const nlohmann::json& a : vj["approximations"]) r.approximations.push_back(a.is_string() ? a.get<std::string>() : a.dump());
    }
    const std::string verify_cmd = "vipars verify mission.yaml --models models.yaml --tmax-range " + tax.range() +
                                   " --rmax-range " + rax.range() + " --json";
    vj["command"] = verify_cmd;
    write_text(folder / "verify.json", vj.dump(2) + "\n");

    // 6. The validation on the same grid, and shifted by -1 % and +1 % for the tolerant scores.
    t0 = std::chrono::steady_clock::now();
    const team_sim::EmpiricalGrid mid = team_sim::empirical_grid(runs, tax.values, rax.values);
    const team_sim::EmpiricalGrid lo =
        team_sim::empirical_grid(runs, scaled(tax.values, 1 - kShiftFraction), scaled(rax.values, 1 - kShiftFraction));
    const team_sim::EmpiricalGrid hi =
        team_sim::empirical_grid(runs, scaled(tax.values, 1 + kShiftFraction), scaled(rax.values, 1 + kShiftFraction));
    const team_sim::EmpiricalPoint at = team_sim::empirical_at(runs, mission.criteria.tmax_s, mission.criteria.rmax_m);
    r.runs = at.runs;
    r.failed_runs = at.failed_runs;
    r.validate_p_joint = at.joint.p;
    vipars::ValidationSummary vs;
    vs.mission_name = mission.name;
    vs.threshold = mission.criteria.threshold;
    vs.point = &at;
    vs.grid = &mid;
    vs.seed = vseed;
    vs.world_file = "world.yaml";
    vs.mission_file = "mission.yaml";
    nlohmann::ordered_json wj = vipars::validation_json(vs);
    const std::string validate_cmd = "vipars validate mission.yaml --world world.yaml --trials " + std::to_string(o.runs) +
                                      " --seed " + std::to_string(vseed) + " --timeout " + format_general(timeout_s, 10) +
                                      " --tmax-range " + tax.range() + " --rmax-range " + rax.range() + " --json";
    wj["command"] = validate_cmd;
    write_text(folder / "validate.json", wj.dump(2) + "\n");
    r.robot_distances = robot_distances(*verified, wj, r.runs, r.failed_runs);

    std::vector<std::vector<double>> vjoint = verified->grid->p_joint;
    std::vector<std::vector<ValidationPoint>> wjoint(tax.values.size());
    for (std::size_t i = 0; i < tax.values.size(); ++i) {
      for (std::size_t j = 0; j < rax.values.size(); ++j) {
        const team_sim::Estimate& e = mid.joint[i][j];
        wjoint[i].push_back({e.p, e.ci_low, e.ci_high, lo.joint[i][j].p, hi.joint[i][j].p});
      }
    }
    // The radius curve both sides can define: completed within the runs' time
    // budget, with every robot within Rmax (see completed_radius_curve()).
    verifier::VerifyOptions at_budget;
    at_budget.tmax_grid = {timeout_s};
    at_budget.rmax_grid = rax.values;
    Result<verifier::VerifyResult> budget_read = verifier::verify_outcome(mission, models, *outcome, at_budget);
    if (!budget_read) throw std::runtime_error("verify: " + budget_read.error().message);
    // What the gate decides on at each cell: the joint probability at its
    // stricter decision point (verifier::decision_point(): separable, so one
    // more read of the same evaluation on mapped axes).
    verifier::VerifyOptions decided_grid;
    const bool widened = verified->widened;
    const verifier::DecisionFloors& floors = verified->floors;
    for (const double t : tax.values) decided_grid.tmax_grid.push_back(verifier::decision_point(t, 1.0, widened, floors).tmax_s);
    for (const double rm : rax.values) {
      decided_grid.rmax_grid.push_back(verifier::decision_point(1.0, rm, widened, floors).rmax_m);
    }
    Result<verifier::VerifyResult> decided_read = verifier::verify_outcome(mission, models, *outcome, decided_grid);
    if (!decided_read) throw std::runtime_error("verify: " + decided_read.error().message);
    r.score = score_mission(tax.values, rax.values, verified->grid->p_time, budget_read->grid->p_joint.front(), vjoint,
                            curve_points(mid.time, lo.time, hi.time), completed_radius_curve(runs, rax.values, timeout_s),
                            wjoint, &decided_read->grid->p_joint);
    // The separation criterion's curve, from the same evaluation and runs.
    if (mission.robots.size() >= 2) r.separation = score_separation(*outcome, runs, o.rmax_points, 2.0 * floors.radius_m);
    r.score_s = seconds_since(t0);

    // 7. How to redo it: the whole mission, or each step in its folder.
    r.reproduce = o.command_prefix + " " +
                  (input.generator_seed ? input.source : "--missions " + input.source + (input.models_yaml.empty() ? "" : " --shipped-models")) +
                  " --runs " + std::to_string(o.runs) + " --seed " + std::to_string(o.seed) +
                  " --calibration-runs " + std::to_string(o.calibration_runs) + " --out " + o.out_dir + "/rerun";
    std::string commands = "# " + input.name + ": how each file here was made (run in this folder)\n";
    commands += "# the whole mission again:\n" + r.reproduce + "\n";
    commands += "# " + r.calibration_note + "\n";
    commands += verify_cmd + " > verify.json\n" + validate_cmd + " > validate.json\n";
    commands += "vipars report --verify verify.json --validate validate.json --mission mission.yaml --models models.yaml "
                "--world world.yaml --out page\n";
    write_text(folder / "commands.txt", commands);
    write_text(folder / "score.json", mission_result_json(r).dump(2) + "\n");
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  say("done");
  return r;
}

double validation_timeout_s(double tmax_s) { return std::max(120.0, 2.0 * tmax_s); }

}  // namespace p3at::crosscheck
