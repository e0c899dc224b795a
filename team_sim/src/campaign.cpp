#include "p3at/team_sim/campaign.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "p3at/common/log.hpp"

namespace p3at::team_sim {

unsigned campaign_jobs(const CampaignOptions& options) {
  unsigned jobs = options.jobs != 0 ? options.jobs : std::thread::hardware_concurrency();
  jobs = std::max(jobs, 1U);
  if (options.runs < jobs) jobs = static_cast<unsigned>(std::max<std::uint64_t>(options.runs, 1));
  return jobs;
}

std::vector<RunResult> run_campaign(const TeamScenario& scenario, const CampaignOptions& options,
                                    const ProgressFn& progress) {
  std::vector<RunResult> results(options.runs);
  RunOptions run_options = options.run;
  run_options.log_transitions = false;

  // Each run lowers the process-wide log threshold to `warn` for its
  // duration and restores it after. Lowering it once here, before any worker
  // starts, means the runs find it already at `warn` and leave it there.
  const log::Level saved_threshold = log::threshold();
  if (saved_threshold < log::Level::warn) log::threshold() = log::Level::warn;

  std::atomic<std::uint64_t> next{0};
  std::atomic<std::uint64_t> done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;

  const auto worker = [&] {
    for (;;) {
      if (stop.load()) break;
      const std::uint64_t i = next.fetch_add(1);
      if (i >= options.runs) break;
      try {
        const std::uint64_t run = options.first_run + i;
        results[i] = scenario.run(run, run_seed(options.seed, run), run_options);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        stop.store(true);
        finished.notify_all();
        break;
      }
      if (done.fetch_add(1) + 1 == options.runs) {
        const std::lock_guard lock(mutex);
        finished.notify_all();
      }
    }
  };

  {
    std::vector<std::jthread> workers;
    const unsigned jobs = campaign_jobs(options);
    workers.reserve(jobs);
    for (unsigned j = 0; j < jobs; ++j) workers.emplace_back(worker);
    std::unique_lock lock(mutex);
    while (done.load() < options.runs && !stop.load()) {
      finished.wait_for(lock, options.progress_every);
      const std::uint64_t so_far = done.load();
      if (progress && so_far < options.runs && !stop.load()) {
        lock.unlock();
        progress(so_far, options.runs);
        lock.lock();
      }
    }
  }  // joins the workers

  log::threshold() = saved_threshold;
  if (error) std::rethrow_exception(error);
  if (progress) progress(options.runs, options.runs);
  return results;
}

}  // namespace p3at::team_sim
