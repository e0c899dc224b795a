#include "p3at/launch_gate/reverifier.hpp"

#include <chrono>
#include <exception>
#include <utility>

namespace p3at::gate {

Reverifier::Reverifier(mission::Mission mission, verifier::Models models, verifier::VerifyOptions options,
                       std::vector<std::string> criteria_files, VerdictSource source)
    : mission_(std::move(mission)),
      models_(std::move(models)),
      options_(std::move(options)),
      criteria_files_(std::move(criteria_files)),
      source_(std::move(source)),
      worker_([this] { work(); }) {}

Reverifier::~Reverifier() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

std::uint64_t Reverifier::request(verifier::TeamSnapshot snapshot, std::string cause) {
  std::uint64_t id = 0;
  {
    std::lock_guard lock(mutex_);
    id = next_id_++;
    if (pending_) ++dropped_;
    pending_ = Job{id, std::move(snapshot), std::move(cause)};
  }
  wake_.notify_one();
  return id;
}

std::vector<Reverification> Reverifier::take() {
  std::lock_guard lock(mutex_);
  std::vector<Reverification> out;
  out.swap(done_);
  return out;
}

void Reverifier::drain() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !pending_ && !busy_; });
}

std::uint64_t Reverifier::requested() const {
  std::lock_guard lock(mutex_);
  return next_id_ - 1;
}

std::uint64_t Reverifier::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

void Reverifier::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return quit_ || pending_.has_value(); });
    if (quit_) break;
    Job job = std::move(*pending_);
    pending_.reset();
    busy_ = true;
    lock.unlock();

    Reverification answer;
    answer.id = job.id;
    answer.at_s = job.snapshot.elapsed_s;
    answer.cause = std::move(job.cause);
    const auto start = std::chrono::steady_clock::now();
    try {
      answer.result = source_(mission_, models_, options_, criteria_files_, &job.snapshot);
    } catch (const std::exception& e) {
      // The control path never sees an exception: it becomes an error answer.
      answer.result = make_error(Error::Code::state, std::string("re-verification threw: ") + e.what());
    }
    answer.compute_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    lock.lock();
    busy_ = false;
    done_.push_back(std::move(answer));
    if (!pending_) idle_.notify_all();
  }
  busy_ = false;
  pending_.reset();
  idle_.notify_all();
}

}  // namespace p3at::gate
