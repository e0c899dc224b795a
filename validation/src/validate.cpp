// vipars validate MISSION --world FILE --trials N [--jobs J] [--seed S]
//   [--tmax S] [--rmax M] [--tmax-range A:B:STEP] [--rmax-range A:B:STEP]
//   [--region-low P] [--region-high P] [--timeout S] [--json] [--csv FILE]
//   [--shard I/N --part FILE]
// (the flags: apps/vipars/validate_cli.cpp; the run: here).
// The validation campaign (the seed paper's 100 real trials, in fast time):
// the real executive against the simulated hardware, N independent runs on J
// threads, and the fraction of runs that met the criteria, on the same
// quantities and grid as `vipars verify`, with 95 % Wilson intervals.
// docs/validation.md. With --shard, only shard I of N's runs, written as a
// part for `vipars merge` (docs/cluster.md).

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "campaign_output.hpp"
#include "p3at/common/vipars_exit.hpp"
#include "p3at/launch_gate/mission_hash.hpp"
#include "p3at/protocols/mission/loader.hpp"
#include "p3at/validation/validate.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/campaign_part.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/run_table.hpp"
#include "p3at/team_sim/team_run.hpp"
#include "p3at/validation/range_arg.hpp"

namespace p3at::vipars {
namespace {

// Every run's result is kept (a few hundred bytes) until the report: 1e6 runs
// stay well under a gigabyte, and take hours anyway.
constexpr std::uint64_t kMaxTrials = 1'000'000;
constexpr unsigned kMaxJobs = 1024;

int bad_input(const std::string& message) {
  std::fprintf(stderr, "vipars validate: %s\n", message.c_str());
  return kExitBadInput;
}

// The flags' values that the parser's own checks cannot express; the message
// says which flag and what was expected.
std::optional<std::string> check_options(const ValidateOptions& o) {
  if (o.trials < 1 || o.trials > kMaxTrials) {
    return "--trials: expected 1.." + std::to_string(kMaxTrials) + ", got " + std::to_string(o.trials);
  }
  if (o.jobs > kMaxJobs) return "--jobs: expected 0 (all cores).." + std::to_string(kMaxJobs);
  if (o.tmax_given && !(o.tmax_s > 0.0 && std::isfinite(o.tmax_s))) return "--tmax: expected seconds > 0";
  if (o.rmax_given && !(o.rmax_m > 0.0 && std::isfinite(o.rmax_m))) return "--rmax: expected metres > 0";
  if (!(o.region_low >= 0.0 && o.region_low <= o.region_high && o.region_high <= 1.0)) {
    return "--region-low/--region-high: expected 0 <= low <= high <= 1";
  }
  if (!(o.timeout_s > 0.0 && o.timeout_s <= 1e6)) return "--timeout: expected simulated seconds in (0, 1e6]";
  if (o.shard.empty() != o.part_file.empty()) return "--shard and --part: expected both or neither";
  if (!o.shard.empty() && (o.json || !o.csv_file.empty())) {
    return "--shard: a shard writes its part only; give --json and --csv to vipars merge";
  }
  return std::nullopt;
}

// "job NAME ARRAYID_TASK" inside a Slurm job array task (or "job NAME ID" in
// a plain job), so a shard's log lines say which job they are; empty elsewhere.
std::string slurm_job_label() {
  const char* name = std::getenv("SLURM_JOB_NAME");
  const char* array_job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* job = std::getenv("SLURM_JOB_ID");
  std::string id;
  if (array_job && task) {
    id = std::string(array_job) + "_" + task;
  } else if (job) {
    id = job;
  } else {
    return {};
  }
  return "job " + std::string(name ? name : "?") + " " + id;
}

// A shard's progress in its log (not a terminal): a line when it starts, at
// every tenth of its runs and at least once a minute, never more often than
// every 2 s, and the last one when it is done. The shard script shows the
// latest in the job's comment (squeue %k).
class ShardProgressLog {
 public:
  ShardProgressLog(std::string shard, std::string job)
      : prefix_("vipars validate: shard " + shard + (job.empty() ? "" : " (" + job + ")") + ": "),
        start_(std::chrono::steady_clock::now()), last_(start_) {}

  void update(std::uint64_t done, std::uint64_t total) {
    const auto now = std::chrono::steady_clock::now();
    const double since_last_s = std::chrono::duration<double>(now - last_).count();
    const std::uint64_t tenth = done * 10 / std::max<std::uint64_t>(total, 1);
    const bool finished = done == total;
    // The first call (after about 0.2 s) always prints, so squeue shows a
    // started shard's progress at once.
    if (printed_ && !finished && since_last_s < 2.0) return;
    if (printed_ && !finished && tenth <= last_tenth_ && since_last_s < 60.0) return;
    printed_ = true;
    last_ = now;
    last_tenth_ = tenth;
    const double secs = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "%s%llu/%llu runs (%.0f%%), %.1f runs/s\n", prefix_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
                 100.0 * static_cast<double>(done) / static_cast<double>(std::max<std::uint64_t>(total, 1)),
                 secs > 0 ? static_cast<double>(done) / secs : 0.0);
    std::fflush(stderr);
  }

 private:
  std::string prefix_;
  std::chrono::steady_clock::time_point start_, last_;
  std::uint64_t last_tenth_ = 0;
  bool printed_ = false;
};

// The content hash a part carries: the launch gate's mission_content_hash
// over the mission file's bytes and the world file's bytes (in the models
// file's place; the world's walls are in its bytes). Parts whose hashes
// differ were made from different files and never merge.
Result<std::string> campaign_content_hash(const std::string& mission_file, const std::string& world_file) {
  auto mission_bytes = gate::read_file_bytes(mission_file);
  if (!mission_bytes) return mission_bytes.error();
  auto world_bytes = gate::read_file_bytes(world_file);
  if (!world_bytes) return world_bytes.error();
  return gate::mission_content_hash(*mission_bytes, *world_bytes, {});
}

// Progress on a terminal: a bar, runs/s and the time left, redrawn in place.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

  void update(std::uint64_t done, std::uint64_t total) {
    if (!enabled_) return;
    constexpr int kWidth = 30;
    const double secs = elapsed_s();
    const double rate = secs > 0 ? static_cast<double>(done) / secs : 0.0;
    const auto filled = static_cast<int>(static_cast<double>(kWidth) * static_cast<double>(done) /
                                         static_cast<double>(std::max<std::uint64_t>(total, 1)));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r[%s] %llu/%llu runs  %.1f runs/s  ", bar.c_str(), static_cast<unsigned long long>(done),
                 static_cast<unsigned long long>(total), rate);
    if (rate > 0 && done < total) {
      const auto left = static_cast<long long>(static_cast<double>(total - done) / rate + 0.5);
      std::fprintf(stderr, "%lld:%02lld left   ", left / 60, left % 60);
    } else {
      std::fprintf(stderr, "          ");
    }
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

int run_validate(ValidateOptions o) {
  if (auto problem = check_options(o)) return bad_input(*problem);
  std::optional<team_sim::Shard> shard;
  if (!o.shard.empty()) {
    auto parsed = team_sim::parse_shard(o.shard);
    if (!parsed) return bad_input("--shard: " + parsed.error().message);
    if (parsed->count > o.trials) {
      return bad_input("--shard: " + std::to_string(parsed->count) + " shards of " + std::to_string(o.trials) +
                       " runs: expected at most one shard per run");
    }
    shard = *parsed;
  }
  // Hashed before loading: the part names the bytes the runs were made from.
  std::string content_hash;
  if (shard) {
    auto hash = campaign_content_hash(o.mission_file, o.world_file);
    if (!hash) return bad_input(hash.error().message);
    content_hash = *hash;
  }
  std::optional<team_sim::TeamScenario> scenario;
  try {
    scenario.emplace(mission::load_mission_file(o.mission_file), sim::load_world_file(o.world_file));
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }
  const mission::Mission& mission = scenario->mission();
  if (!o.tmax_given) o.tmax_s = mission.criteria.tmax_s;
  if (!o.rmax_given) o.rmax_m = mission.criteria.rmax_m;

  // What the runs are counted against, and what the report prints: the same
  // description for a whole campaign and for a shard's part.
  team_sim::CampaignHeader campaign;
  campaign.content_hash = content_hash;
  campaign.seed = o.seed;
  campaign.trials = o.trials;
  campaign.timeout_s = o.timeout_s;
  campaign.tmax_s = o.tmax_s;
  campaign.rmax_m = o.rmax_m;
  campaign.has_grid = !o.tmax_range.empty() || !o.rmax_range.empty();
  campaign.tmax_axis = {o.tmax_s};
  campaign.rmax_axis = {o.rmax_m};
  for (auto [flag, text, axis] : {std::tuple{"--tmax-range", &o.tmax_range, &campaign.tmax_axis},
                                  std::tuple{"--rmax-range", &o.rmax_range, &campaign.rmax_axis}}) {
    if (text->empty()) continue;
    auto parsed = parse_range(*text);
    if (!parsed) return bad_input(std::string(flag) + ": " + parsed.error().message);
    *axis = std::move(parsed).value();
  }
  campaign.region_low = o.region_low;
  campaign.region_high = o.region_high;
  campaign.mission_name = mission.name;
  campaign.threshold = mission.criteria.threshold;
  for (const auto& r : mission.robots) campaign.robots.push_back(r.name);
  campaign.mission_file = o.mission_file;
  campaign.world_file = o.world_file;

  std::ofstream csv;
  if (!o.csv_file.empty()) {
    csv.open(o.csv_file);
    if (!csv) return bad_input("cannot write " + o.csv_file);
  }

  team_sim::CampaignOptions options;
  const team_sim::RunRange range = shard ? team_sim::shard_runs(o.trials, *shard) : team_sim::RunRange{0, o.trials};
  options.first_run = range.first;
  options.runs = range.size();
  options.seed = o.seed;
  options.jobs = o.jobs;
  options.run.timeout_s = o.timeout_s;
  const unsigned jobs = team_sim::campaign_jobs(options);
  const bool terminal = isatty(STDERR_FILENO) != 0;
  ProgressBar bar(terminal);
  std::optional<ShardProgressLog> shard_log;
  if (shard && !terminal) shard_log.emplace(team_sim::to_string(*shard), slurm_job_label());
  std::vector<team_sim::RunResult> runs;
  try {
    runs = team_sim::run_campaign(*scenario, options, [&](std::uint64_t done, std::uint64_t total) {
      bar.update(done, total);
      if (shard_log) shard_log->update(done, total);
    });
  } catch (const std::exception& e) {
    // A run throws only when the simulator cannot be built from the world
    // file (e.g. radio parameters): bad input, the same for every run.
    return bad_input(e.what());
  }
  const double wall_s = bar.elapsed_s();

  std::uint64_t failed = 0;
  if (shard) {
    const team_sim::CampaignPart part = team_sim::make_part(campaign, *shard, std::move(runs));
    if (auto written = team_sim::write_part_file(o.part_file, part); !written) return bad_input(written.error().message);
    failed = part.counts.failed;
  } else {
    if (csv.is_open() && !write_validation_csv(csv, campaign.robots, runs)) return bad_input("cannot write " + o.csv_file);
    failed = print_campaign_report(campaign, runs, o.json).failed_runs;
  }
  // One grep-able line for logs; on stderr so stdout stays identical across runs.
  std::fprintf(stderr, "vipars validate: %sruns=%llu failed=%llu jobs=%u wall_s=%.2f runs_per_s=%.1f\n",
               shard ? ("shard=" + team_sim::to_string(*shard) + " part=" + o.part_file + " ").c_str() : "",
               static_cast<unsigned long long>(range.size()), static_cast<unsigned long long>(failed), jobs, wall_s,
               wall_s > 0 ? static_cast<double>(range.size()) / wall_s : 0.0);
  // A shard's failed runs are results (in its part); whether the whole
  // campaign failed is merge's to say.
  if (shard) return kExitOk;
  return failed == range.size() ? kExitFailed : kExitOk;
}

}  // namespace p3at::vipars
