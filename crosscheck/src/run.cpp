// run_crosscheck(): the missions in order, a progress bar (or plain lines),
// one line per mission, the summary, the JSON, the report and the baseline
// check (run.hpp).

#include "p3at/crosscheck/run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "p3at/crosscheck/baseline.hpp"
#include "p3at/crosscheck/campaign_report.hpp"
#include "p3at/crosscheck/result_json.hpp"
#include "p3at/crosscheck/shard_part.hpp"
#include "p3at/common/vipars_exit.hpp"

namespace p3at::crosscheck {
namespace {

using vipars::kExitBadInput;
using vipars::kExitFailed;
using vipars::kExitOk;
constexpr int kExitWorse = 1;  ///< a mission worse than its baseline

// One line on stderr, redrawn in place on a terminal.
class Progress {
 public:
  Progress(std::size_t missions) : missions_(missions), tty_(isatty(STDERR_FILENO) == 1), t0_(clock::now()) {}

  void update(std::size_t index, const std::string& name, const std::string& phase, std::uint64_t done, std::uint64_t total) {
    if (!tty_) return;
    const auto now = clock::now();
    if (phase == "validating" && done != total && now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    const double frac = (static_cast<double>(index) + (total ? static_cast<double>(done) / static_cast<double>(total) : 0.0)) /
                        static_cast<double>(missions_);
    const int width = 30;
    const int filled = static_cast<int>(frac * width);
    const double elapsed = std::chrono::duration<double>(now - t0_).count();
    const double left = frac > 0.01 ? elapsed * (1 - frac) / frac : 0.0;
    std::fprintf(stderr, "\r[%.*s%.*s] %zu/%zu %-14s %s", filled, "##############################", width - filled,
                 "..............................", index + 1, missions_, name.c_str(), phase.c_str());
    if (phase == "validating") std::fprintf(stderr, " %llu/%llu runs", static_cast<unsigned long long>(done), static_cast<unsigned long long>(total));
    if (frac > 0.01) std::fprintf(stderr, ", %.0f s left", left);
    std::fprintf(stderr, "      ");
    std::fflush(stderr);
  }
  void finished(std::size_t index, const MissionResult& r) {
    if (tty_) {
      std::fprintf(stderr, "\r%100s\r", "");
      return;
    }
    std::fprintf(stderr, "vipars crosscheck: %zu/%zu %s %s in %.1f s%s\n", index + 1, missions_, r.name.c_str(),
                 r.error.empty() ? "done" : "could not run", r.calibrate_s + r.verify_s + r.validate_s + r.score_s,
                 r.runs_reused ? " (validation runs reused from its runs.part)" : "");
  }

 private:
  using clock = std::chrono::steady_clock;
  std::size_t missions_;
  bool tty_;
  clock::time_point t0_, last_{};
};

std::string command_line(const CrosscheckRun& run) {
  std::string c = run.campaign.command_prefix;
  if (run.from_results) return c + " --from-results --out " + run.campaign.out_dir;
  if (run.first_seed) {
    c += " --seeds " + std::to_string(*run.first_seed) + ":" + std::to_string(*run.last_seed) + " --robots " +
         std::to_string(run.min_robots) + ":" + std::to_string(run.max_robots);
  }
  if (!run.folders.empty()) {
    c += " --missions";
    for (const std::string& f : run.folders) c += " " + f;
    if (run.shipped_models) c += " --shipped-models";
  }
  c += " --runs " + std::to_string(run.campaign.runs) + " --seed " + std::to_string(run.campaign.seed) +
       " --calibration-runs " + std::to_string(run.campaign.calibration_runs) + " --out " + run.campaign.out_dir;
  return c;
}

// The campaign's end, the same for a whole campaign and for merged shards:
// crosscheck.json, summary.txt, stdout (text or JSON), the report, the
// baseline, the exit status.
int finish_campaign(const CrosscheckRun& run, const std::vector<MissionResult>& results, const std::string& command,
                    double wall_s, const std::vector<BaselineEntry>& baseline) {
  const Bounds bounds;
  const CampaignSummary summary = summarize(results, bounds);
  nlohmann::ordered_json doc;
  doc["command"] = command;
  doc["runs_per_mission"] = run.campaign.runs;
  doc["seed"] = run.campaign.seed;
  doc["summary"] = summary_json(summary, bounds);
  doc["missions"] = nlohmann::ordered_json::array();
  for (const MissionResult& r : results) doc["missions"].push_back(mission_result_json(r));
  int status = kExitOk;
  const std::filesystem::path out(run.campaign.out_dir);
  {
    std::ofstream f(out / "crosscheck.json");
    f << doc.dump(2) << "\n";
    std::ofstream t(out / "summary.txt");
    t << "# " << command << "\n";
    for (const MissionResult& r : results) t << mission_line(r, bounds) << "\n";
    t << summary_text(summary, bounds);
    if (!f || !t) status = kExitFailed;
  }
  if (run.json) {
    std::printf("%s\n", doc.dump(2).c_str());
  } else {
    std::printf("\n%s", summary_text(summary, bounds).c_str());
    bool listed = false;
    for (const MissionResult& r : results) {
      if (!r.evaluable && r.error.empty()) {
        if (!listed) std::printf("verify cannot evaluate (scored, left out of the over-confident GO count):\n");
        listed = true;
        std::printf("  %s: %zu approximation%s\n", r.name.c_str(), r.approximations.size(), r.approximations.size() == 1 ? "" : "s");
      }
    }
    // The worst failing missions, each with the one command that redoes it alone.
    std::vector<const MissionResult*> failing;
    for (const MissionResult& r : results) {
      if (mission_fails(r, bounds) && !r.reproduce.empty()) failing.push_back(&r);
    }
    std::stable_sort(failing.begin(), failing.end(), [](const MissionResult* a, const MissionResult* b) {
      const auto worst = [](const MissionResult* m) {
        return std::max({m->score.time.tolerant, m->score.radius.tolerant, m->score.joint.tolerant});
      };
      return worst(a) > worst(b);
    });
    if (!failing.empty()) std::printf("worst failing missions, each redone alone by:\n");
    for (std::size_t k = 0; k < failing.size() && k < 10; ++k) {
      std::printf("  %s: %s\n", failing[k]->name.c_str(), failing[k]->reproduce.c_str());
    }
    std::printf("every mission's files and commands: %s/missions/NAME/ (commands.txt)\n", run.campaign.out_dir.c_str());
  }
  if (run.report) {
    ReportOptions ro;
    ro.out_dir = run.campaign.out_dir;
    ro.gnuplot = run.campaign.gnuplot;
    ro.command = command;
    for (const std::string& p : write_campaign_report(results, summary, bounds, ro)) {
      std::fprintf(stderr, "vipars crosscheck: report: %s\n", p.c_str());
    }
    std::fprintf(stderr, "vipars crosscheck: report %s/index.html\n", run.campaign.out_dir.c_str());
  }
  if (!run.write_baseline.empty()) {
    std::ofstream b(run.write_baseline);
    b << baseline_json(baseline_from(results, bounds, run.baseline_margin), command).dump(2) << "\n";
    if (!b) {
      std::fprintf(stderr, "vipars crosscheck: cannot write %s\n", run.write_baseline.c_str());
      status = kExitFailed;
    }
  }
  for (const MissionResult& r : results) {
    if (!r.error.empty()) status = kExitFailed;
  }
  if (!run.baseline.empty()) {
    const std::vector<std::string> worse = check_baseline(results, baseline);
    for (const std::string& w : worse) std::fprintf(stderr, "vipars crosscheck: worse than %s: %s\n", run.baseline.c_str(), w.c_str());
    if (!worse.empty() && status == kExitOk) status = kExitWorse;
    if (worse.empty()) std::fprintf(stderr, "vipars crosscheck: every mission within %s\n", run.baseline.c_str());
  }
  std::fprintf(stderr, "vipars crosscheck: missions=%zu runs=%llu wall_s=%.1f\n", results.size(),
               static_cast<unsigned long long>(summary.runs), wall_s);
  return status;
}

}  // namespace

int run_crosscheck(const CrosscheckRun& run) {
  if (run.from_results) {
    // A campaign's missions.jsonl (possibly of a campaign stopped part-way): only the output.
    std::vector<MissionResult> results;
    const std::filesystem::path path = std::filesystem::path(run.campaign.out_dir) / "missions.jsonl";
    std::ifstream in(path);
    if (!in) {
      std::fprintf(stderr, "vipars crosscheck: cannot read %s\n", path.string().c_str());
      return kExitBadInput;
    }
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (line.empty()) continue;
      try {
        results.push_back(mission_result_from_json(nlohmann::json::parse(line)));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "vipars crosscheck: %s:%d: not a mission's result (%s)\n", path.string().c_str(), n, e.what());
        return kExitBadInput;
      }
    }
    if (results.empty()) {
      std::fprintf(stderr, "vipars crosscheck: %s holds no missions\n", path.string().c_str());
      return kExitBadInput;
    }
    std::vector<BaselineEntry> baseline;
    if (!run.baseline.empty()) {
      try {
        baseline = load_baseline(run.baseline);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "vipars crosscheck: %s\n", e.what());
        return kExitBadInput;
      }
    }
    return finish_campaign(run, results, command_line(run), 0.0, baseline);
  }
  std::vector<MissionInput> inputs;
  try {
    if (run.first_seed) inputs = generated_inputs(*run.first_seed, *run.last_seed, run.min_robots, run.max_robots);
    std::vector<MissionInput> more = folder_inputs(run.folders, run.shipped_models);
    for (MissionInput& m : more) inputs.push_back(std::move(m));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars crosscheck: %s\n", e.what());
    return kExitBadInput;
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "vipars crosscheck: no missions: give --seeds A:B and/or --missions DIR...\n");
    return kExitBadInput;
  }
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (inputs[i].name == inputs[j].name) {
        std::fprintf(stderr, "vipars crosscheck: two missions are named '%s' (%s and %s): their folders would collide\n",
                     inputs[i].name.c_str(), inputs[j].source.c_str(), inputs[i].source.c_str());
        return kExitBadInput;
      }
    }
  }
  std::vector<BaselineEntry> baseline;
  if (!run.baseline.empty()) {
    try {
      baseline = load_baseline(run.baseline);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vipars crosscheck: %s\n", e.what());
      return kExitBadInput;
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(run.campaign.out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "vipars crosscheck: cannot create %s: %s\n", run.campaign.out_dir.c_str(), ec.message().c_str());
    return kExitFailed;
  }

  // A shard cross-checks only its share of the missions, in the same order
  // (docs/cluster.md); the others' folders are other shards' to write.
  const std::vector<MissionInput> all_inputs = inputs;
  team_sim::RunRange range{0, inputs.size()};
  if (run.shard) {
    if (run.shard->count > inputs.size()) {
      std::fprintf(stderr, "vipars crosscheck: --shard: %llu shards of %zu missions: expected at most one shard per mission\n",
                   static_cast<unsigned long long>(run.shard->count), inputs.size());
      return kExitBadInput;
    }
    range = team_sim::shard_runs(inputs.size(), *run.shard);
    inputs.assign(all_inputs.begin() + static_cast<std::ptrdiff_t>(range.first),
                  all_inputs.begin() + static_cast<std::ptrdiff_t>(range.end));
  }

  const Bounds bounds;
  Progress progress(inputs.size());
  bool any_runs_only_error = false;
  std::vector<MissionResult> results;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    MissionResult r = run_mission(inputs[i], run.campaign, [&](const std::string& phase, std::uint64_t done, std::uint64_t total) {
      progress.update(i, inputs[i].name, phase, done, total);
    });
    progress.finished(i, r);
    if (r.runs_only) {
      if (!r.error.empty()) std::printf("%s: could not make its runs: %s\n", r.name.c_str(), r.error.c_str());
      else std::printf("%s: %llu runs %s %s/runs.part\n", r.name.c_str(), static_cast<unsigned long long>(r.runs),
                       r.runs_reused ? "already in" : "kept in", r.folder.c_str());
      std::fflush(stdout);
      if (!r.error.empty()) any_runs_only_error = true;
      continue;
    }
    if (!run.shard) {
      // As each mission ends, so that a campaign stopped part-way still leaves its results
      // (a shard's record is its part: shards share the folder).
      std::ofstream partial(std::filesystem::path(run.campaign.out_dir) / "missions.jsonl", i == 0 ? std::ios::trunc : std::ios::app);
      partial << mission_result_json(r).dump() << "\n";
    }
    if (!run.json) {
      std::printf("%s\n", mission_line(r, bounds).c_str());
      std::fflush(stdout);
    }
    results.push_back(std::move(r));
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (run.campaign.runs_only) {
    std::fprintf(stderr, "vipars crosscheck: --runs-only: the runs of %zu missions are in %s/missions/NAME/runs.part "
                         "(%.0f s); score them with the same command and --reuse-runs instead of --runs-only\n",
                 inputs.size(), run.campaign.out_dir.c_str(), wall_s);
    return any_runs_only_error ? 3 : 0;
  }
  if (run.shard) {
    CrosscheckPart part;
    part.header.identity = campaign_identity(all_inputs, run.campaign);
    part.header.command = command_line(run);
    for (const MissionInput& m : all_inputs) part.header.names.push_back(m.name);
    part.header.shard = *run.shard;
    part.header.missions = range;
    part.header.out_dir = run.campaign.out_dir;
    part.header.gnuplot = run.campaign.gnuplot;
    part.header.report = run.report;
    part.header.baseline = run.baseline;
    part.header.write_baseline = run.write_baseline;
    part.header.baseline_margin = run.baseline_margin;
    part.header.runs_per_mission = run.campaign.runs;
    part.header.seed = run.campaign.seed;
    part.results = std::move(results);
    if (auto written = write_crosscheck_part_file(run.part_file, part); !written) {
      std::fprintf(stderr, "vipars crosscheck: %s\n", written.error().message.c_str());
      return kExitFailed;
    }
    std::fprintf(stderr, "vipars crosscheck: shard=%s part=%s missions=%zu wall_s=%.1f\n",
                 team_sim::to_string(*run.shard).c_str(), run.part_file.c_str(), part.results.size(), wall_s);
    return kExitOk;
  }
  return finish_campaign(run, results, command_line(run), wall_s, baseline);
}

int merge_crosscheck(const std::vector<std::string>& part_files, bool json) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<NamedCrosscheckPart> parts;
  std::size_t missions_read = 0;
  for (const std::string& file : part_files) {
    auto part = read_crosscheck_part_file(file);
    if (!part) {
      std::fprintf(stderr, "vipars merge: %s\n", part.error().message.c_str());
      return kExitBadInput;
    }
    missions_read += part->results.size();
    parts.push_back({file, std::move(part).value()});
  }
  if (parts.empty()) {
    std::fprintf(stderr, "vipars merge: no parts given\n");
    return kExitBadInput;
  }
  const std::size_t expected = parts.front().part.header.names.size();
  const std::size_t part_count = parts.size();
  auto merged = merge_crosscheck_parts(std::move(parts));
  if (!merged) {
    std::fprintf(stderr, "vipars merge: %s\n", merged.error().message.c_str());
    std::fprintf(stderr, "vipars merge: merged %zu of %zu missions expected from %zu parts: refused, no result written\n",
                 missions_read, expected, part_count);
    return kExitBadInput;
  }
  std::fprintf(stderr, "vipars merge: merged %zu of %zu missions expected from %zu parts\n", merged->results.size(),
               expected, part_count);
  // The unsharded campaign's outputs, as its shards were told them.
  CrosscheckRun run;
  run.campaign.out_dir = merged->header.out_dir;
  run.campaign.gnuplot = merged->header.gnuplot;
  run.report = merged->header.report;
  run.baseline = merged->header.baseline;
  run.write_baseline = merged->header.write_baseline;
  run.baseline_margin = merged->header.baseline_margin;
  run.campaign.runs = merged->header.runs_per_mission;
  run.campaign.seed = merged->header.seed;
  run.json = json;
  std::vector<BaselineEntry> baseline;
  if (!run.baseline.empty()) {
    try {
      baseline = load_baseline(run.baseline);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vipars merge: %s\n", e.what());
      return kExitBadInput;
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(run.campaign.out_dir, ec);
  if (!run.json) {
    const Bounds bounds;
    for (const MissionResult& r : merged->results) std::printf("%s\n", mission_line(r, bounds).c_str());
    std::fflush(stdout);
  }
  {
    // The unsharded campaign's record of each mission, in order.
    std::ofstream partial(std::filesystem::path(run.campaign.out_dir) / "missions.jsonl", std::ios::trunc);
    for (const MissionResult& r : merged->results) partial << mission_result_json(r).dump() << "\n";
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish_campaign(run, merged->results, merged->command, wall_s, baseline);
}

}  // namespace p3at::crosscheck
