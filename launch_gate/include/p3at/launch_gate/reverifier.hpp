#pragma once
/// In-mission re-verification off the control path: the executive's thread
/// hands over a snapshot of where the team is (request(), never blocks) and
/// picks up finished answers later (take(), never blocks); one worker thread
/// runs the verifier meanwhile, so a slow verification cannot overrun the
/// 100 ms cycle. Only the newest request is kept: a snapshot that was not
/// started before a newer one arrived is dropped (and counted).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::gate {

struct Reverification {
  std::uint64_t id = 0;          ///< request number, from 1
  double at_s = 0.0;             ///< the snapshot's mission time
  std::string cause;             ///< what prompted it (e.g. "robot1:bound_ow2")
  Result<verifier::VerifyResult> result{verifier::VerifyResult{}};
  double compute_ms = 0.0;       ///< the verifier call, on the worker thread
};

class Reverifier {
 public:
  /// Copies everything it needs. `source` is only ever called from the
  /// worker thread (one call at a time).
  Reverifier(mission::Mission mission, verifier::Models models, verifier::VerifyOptions options,
             std::vector<std::string> criteria_files, VerdictSource source);
  ~Reverifier();  ///< finishes the verification in progress, drops pending ones, joins
  Reverifier(const Reverifier&) = delete;
  Reverifier& operator=(const Reverifier&) = delete;

  /// Queues a re-verification from `snapshot` (replacing one not yet started).
  /// Returns its id.
  std::uint64_t request(verifier::TeamSnapshot snapshot, std::string cause);
  /// The answers finished since the last call, oldest first.
  std::vector<Reverification> take();
  /// Blocks until every request so far is answered (tests, shutdown reports).
  void drain();

  std::uint64_t requested() const;
  std::uint64_t dropped() const;  ///< replaced before they started

 private:
  struct Job {
    std::uint64_t id = 0;
    verifier::TeamSnapshot snapshot;
    std::string cause;
  };
  void work();

  const mission::Mission mission_;
  const verifier::Models models_;
  const verifier::VerifyOptions options_;
  const std::vector<std::string> criteria_files_;
  VerdictSource source_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::optional<Job> pending_;
  bool busy_ = false;
  bool quit_ = false;
  std::uint64_t next_id_ = 1;
  std::uint64_t dropped_ = 0;
  std::vector<Reverification> done_;
  std::thread worker_;  ///< last: started once everything above exists
};

}  // namespace p3at::gate
