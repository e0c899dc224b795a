#include "p3at/report/report_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <tuple>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"
#include "p3at/validation/range_arg.hpp"
#include "p3at/report/command_lines.hpp"
#include "p3at/validation/validation_json.hpp"
#include "p3at/validation/verify_output.hpp"

namespace p3at::vipars::report {
namespace {

using Json = nlohmann::ordered_json;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The stand-alone commands giving the same documents (both are deterministic).
std::string standalone(const RunRequest& r, bool verify) {
  std::vector<std::string> words{"vipars", verify ? "verify" : "validate", r.mission_file};
  if (verify) {
    words.insert(words.end(), {"--models", r.models_file});
  } else {
    words.insert(words.end(), {"--world", r.world_file, "--trials", std::to_string(r.trials), "--seed",
                               std::to_string(r.seed), "--timeout", format_general(r.timeout_s, 15)});
  }
  if (r.tmax_s) words.insert(words.end(), {"--tmax", format_general(*r.tmax_s, 15)});
  if (r.rmax_m) words.insert(words.end(), {"--rmax", format_general(*r.rmax_m, 15)});
  words.insert(words.end(), {"--tmax-range", r.tmax_range, "--rmax-range", r.rmax_range, "--region-low",
                             format_general(r.thresholds.low, 15), "--region-high", format_general(r.thresholds.high, 15), "--json"});
  return shell_join(words);
}

}  // namespace

Result<RunOutput> run_verify_and_validate(const RunRequest& r,
                                          const std::function<void(const std::string&)>& progress) {
  const auto say = [&progress](const std::string& line) {
    if (progress) progress(line);
  };
  if (r.trials < 1 || r.trials > 1'000'000) {
    return make_error(Error::Code::invalid_argument, "--trials: expected 1..1000000, got " + std::to_string(r.trials));
  }
  std::vector<double> tmax_axis, rmax_axis;
  for (auto [flag, text, axis] :
       {std::tuple{"--tmax-range", &r.tmax_range, &tmax_axis}, std::tuple{"--rmax-range", &r.rmax_range, &rmax_axis}}) {
    if (text->empty()) return make_error(Error::Code::invalid_argument, std::string(flag) + ": required (A:B:STEP)");
    auto parsed = parse_range(*text);
    if (!parsed) return make_error(Error::Code::invalid_argument, std::string(flag) + ": " + parsed.error().message);
    *axis = std::move(parsed).value();
  }
  std::optional<mission::Mission> mission;
  std::optional<verifier::Models> models;
  std::optional<team_sim::TeamScenario> scenario;
  try {
    mission = mission::load_mission_file(r.mission_file);
    models = verifier::load_models_file(r.models_file);
    scenario.emplace(*mission, sim::load_world_file(r.world_file));
  } catch (const std::exception& e) {
    return make_error(Error::Code::invalid_argument, e.what());
  }

  RunOutput out;
  verifier::VerifyOptions options;
  options.tmax_s = r.tmax_s;
  options.rmax_m = r.rmax_m;
  options.tmax_grid = tmax_axis;
  options.rmax_grid = rmax_axis;
  options.region_low = r.thresholds.low;
  options.region_high = r.thresholds.high;
  say("verifying " + r.mission_file + " on a " + std::to_string(tmax_axis.size()) + " x " +
      std::to_string(rmax_axis.size()) + " grid");
  const auto v0 = std::chrono::steady_clock::now();
  Result<verifier::VerifyResult> verified = verifier::verify(*mission, *models, options);
  out.verify_wall_s = seconds_since(v0);
  if (!verified) return verified.error();
  say("verified in " + format_fixed(out.verify_wall_s, 3) + " s: P(success) " + format_fixed(verified->p_joint, 4));
  locate_from_file(*verified, r.mission_file);
  nlohmann::json vj = verify_json(*mission, *verified);
  vj["command"] = standalone(r, true);
  out.verification = Json::parse(vj.dump());  // into the ordered type the caller holds

  team_sim::CampaignOptions campaign;
  campaign.runs = r.trials;
  campaign.seed = r.seed;
  campaign.jobs = r.jobs;
  campaign.run.timeout_s = r.timeout_s;
  campaign.progress_every = std::chrono::milliseconds(1000);
  out.jobs = team_sim::campaign_jobs(campaign);
  say("validating: " + std::to_string(r.trials) + " runs on " + std::to_string(out.jobs) + " thread(s)");
  const auto w0 = std::chrono::steady_clock::now();
  std::uint64_t last_tenth = 0;
  std::vector<team_sim::RunResult> runs;
  try {
    runs = team_sim::run_campaign(*scenario, campaign, [&](std::uint64_t done, std::uint64_t total) {
      const std::uint64_t tenth = done * 10 / std::max<std::uint64_t>(total, 1);
      if (tenth == last_tenth || done == total) return;
      last_tenth = tenth;
      const double s = seconds_since(w0);
      say("  " + std::to_string(done) + "/" + std::to_string(total) + " runs, " +
          format_fixed(s > 0 ? static_cast<double>(done) / s : 0.0, 1) + " runs/s");
    });
  } catch (const std::exception& e) {
    return make_error(Error::Code::invalid_argument, e.what());
  }
  out.validate_wall_s = seconds_since(w0);
  const double tmax = r.tmax_s.value_or(mission->criteria.tmax_s);
  const double rmax = r.rmax_m.value_or(mission->criteria.rmax_m);
  const team_sim::EmpiricalPoint point = team_sim::empirical_at(runs, tmax, rmax);
  const team_sim::EmpiricalGrid grid = team_sim::empirical_grid(runs, tmax_axis, rmax_axis);
  say("validated in " + format_fixed(out.validate_wall_s, 1) + " s (" +
      format_fixed(static_cast<double>(r.trials) / std::max(out.validate_wall_s, 1e-9), 1) + " runs/s), " +
      std::to_string(point.failed_runs) + " failed: P(success) " + format_fixed(point.joint.p, 4));
  ValidationSummary summary;
  summary.mission_name = mission->name;
  summary.threshold = mission->criteria.threshold;
  summary.point = &point;
  summary.grid = &grid;
  summary.region_low = r.thresholds.low;
  summary.region_high = r.thresholds.high;
  summary.seed = r.seed;
  summary.world_file = r.world_file;
  summary.mission_file = r.mission_file;
  out.validation = validation_json(summary);
  out.validation["command"] = standalone(r, false);
  return out;
}

}  // namespace p3at::vipars::report
