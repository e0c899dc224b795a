#include "p3at/launch_gate/gate_team_link.hpp"

#include <utility>

namespace p3at::gate {

Status GateTeamLink::poll(std::int64_t, std::vector<hal::TeamNotification>& received) {
  const std::int64_t now_us = link_clock_.now_us();
  received.insert(received.end(), early_.begin(), early_.end());
  early_.clear();
  Status st = inner_.poll(now_us, received);
  if (verdict_ && (!next_verdict_us_ || now_us >= *next_verdict_us_)) {
    const Status published = inner_.publish_verdict(*verdict_);
    if (published) ++verdicts_republished_;
    if (!published && st) st = published;
    next_verdict_us_ = now_us + republish_us_;
  }
  if (after_poll) after_poll();
  return st;
}

Status GateTeamLink::publish_status(const hal::TeamStatus& status) {
  last_status_ = status;
  hal::TeamStatus out = status;
  if (p_success_) out.p_success = *p_success_;
  if (out.phase == "running" && out.reason.empty()) out.reason = note_;
  return inner_.publish_status(out);
}

void GateTeamLink::hand_over(std::vector<hal::TeamNotification> early) {
  early_.insert(early_.end(), std::make_move_iterator(early.begin()), std::make_move_iterator(early.end()));
}

void GateTeamLink::keep_publishing(gate::GateVerdict verdict, std::int64_t republish_us) {
  verdict_ = std::move(verdict);
  republish_us_ = republish_us;
  next_verdict_us_.reset();
}

void GateTeamLink::set_p_success(double p_success) {
  p_success_ = p_success;
  if (last_status_) (void)publish_status(*last_status_);
}

}  // namespace p3at::gate
