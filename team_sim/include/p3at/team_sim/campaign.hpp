#pragma once
/// A validation campaign: many independent fast-time runs of one scenario,
/// spread over worker threads. Run i's seed depends only on (campaign seed,
/// i) and results are stored by index, so a campaign gives the same results
/// whatever the number of threads or the order in which runs finish.

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "p3at/team_sim/run_seed.hpp"
#include "p3at/team_sim/team_run.hpp"

namespace p3at::team_sim {

struct CampaignOptions {
  std::uint64_t runs = 1;
  std::uint64_t first_run = 0;              ///< makes runs first_run .. first_run + runs - 1 (a shard)
  std::uint64_t seed = 1;                   ///< campaign seed; run i uses run_seed(seed, i)
  unsigned jobs = 0;                        ///< worker threads; 0 = hardware concurrency
  RunOptions run;                           ///< for every run (log_transitions is forced off: runs interleave)
  std::chrono::milliseconds progress_every{200};
};

/// Called on the calling thread about every progress_every, and once at the
/// end, with the number of runs finished so far.
using ProgressFn = std::function<void(std::uint64_t done, std::uint64_t total)>;

/// The number of threads a campaign with these options uses (>= 1, <= runs).
unsigned campaign_jobs(const CampaignOptions& options);

/// Runs the campaign; result i is run first_run + i. Blocks until every run is done. An
/// exception thrown by a run (a scenario the simulator cannot build) stops
/// the other workers and is rethrown here.
std::vector<RunResult> run_campaign(const TeamScenario& scenario, const CampaignOptions& options,
                                    const ProgressFn& progress = {});

}  // namespace p3at::team_sim
