#include "p3at/team_link/replay_window.hpp"

namespace p3at::hal {

ReplayWindow::Verdict ReplayWindow::check(std::uint64_t seq) const {
  if (!any_ || seq > highest_) return Verdict::fresh;
  const std::uint64_t behind = highest_ - seq;
  if (behind >= kSize) return Verdict::too_old;
  return seen_.test(behind) ? Verdict::duplicate : Verdict::fresh;
}

ReplayWindow::Verdict ReplayWindow::accept(std::uint64_t seq) {
  const Verdict verdict = check(seq);
  if (verdict != Verdict::fresh) return verdict;
  if (!any_) {
    any_ = true;
    highest_ = seq;
    seen_.reset();
    seen_.set(0);
  } else if (seq > highest_) {
    const std::uint64_t ahead = seq - highest_;
    if (ahead >= kSize) {
      seen_.reset();
    } else {
      seen_ <<= ahead;
    }
    seen_.set(0);
    highest_ = seq;
  } else {
    seen_.set(highest_ - seq);
  }
  return verdict;
}

}  // namespace p3at::hal
