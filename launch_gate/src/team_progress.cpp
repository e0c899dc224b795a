#include "p3at/launch_gate/team_progress.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "p3at/executive/frames.hpp"

namespace p3at::gate {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// The states of `spec` that notify `message`.
std::vector<std::size_t> notify_states(const mission::RobotSpec& spec, const std::string& message) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < spec.states.size(); ++i) {
    if (const auto* n = std::get_if<mission::NotifyParams>(&spec.states[i].behavior); n != nullptr && n->message == message) {
      out.push_back(i);
    }
  }
  return out;
}

}  // namespace

TeamProgress::TeamProgress(const mission::Mission& mission, std::size_t self)
    : mission_(mission), self_(self), last_cycles_(mission.robots.size()) {
  for (const mission::RobotSpec& spec : mission.robots) {
    RobotProgress r;
    r.state = spec.initial;
    r.x_m = spec.start.x_m;
    r.y_m = spec.start.y_m;
    r.theta_rad = spec.start.theta_deg * kDegToRad;
    r.visited.assign(spec.states.size(), false);
    if (r.state < r.visited.size()) r.visited[r.state] = true;
    r.finished = spec.is_final(r.state);
    robots_.push_back(std::move(r));
  }
  robots_.at(self).heard = true;
}

void TeamProgress::move(RobotProgress& r, double t_s, std::size_t state, double x_m, double y_m, double theta_rad) {
  if (state != r.state) {
    r.state = state;
    r.entered_s = t_s;
    if (state < r.visited.size()) r.visited[state] = true;
  }
  r.travelled_m += std::hypot(x_m - r.x_m, y_m - r.y_m);
  r.turned_rad += std::abs(exec::wrap_angle_rad(theta_rad - r.theta_rad));
  r.x_m = x_m;
  r.y_m = y_m;
  r.theta_rad = theta_rad;
}

void TeamProgress::observe_self(double t_s, std::size_t state, const exec::Pose<double>& pose, bool finished) {
  RobotProgress& r = robots_.at(self_);
  move(r, t_s, state, pose.x_m, pose.y_m, pose.theta_rad);
  r.finished = finished;
}

void TeamProgress::observe_teammates(double t_s, const std::vector<hal::Telemetry>& telemetry,
                                     const std::vector<hal::TeamStatus>& status) {
  for (const hal::Telemetry& t : telemetry) {
    const std::optional<std::size_t> index = mission_.find_robot(t.robot);
    if (!index || *index == self_) continue;
    const std::optional<std::size_t> state = mission_.robots[*index].find_state(t.state);
    if (!state) continue;
    // Telemetry is held until replaced: use each sample once.
    if (last_cycles_[*index] && *last_cycles_[*index] == t.cycles) continue;
    last_cycles_[*index] = t.cycles;
    RobotProgress& r = robots_[*index];
    r.heard = true;
    move(r, t_s, *state, t.x_m, t.y_m, t.theta_rad);
    if (mission_.robots[*index].is_final(*state)) r.finished = true;
  }
  for (const hal::TeamStatus& s : status) {
    const std::optional<std::size_t> index = mission_.find_robot(s.robot);
    if (!index || *index == self_) continue;
    if (s.phase == "finished") robots_[*index].finished = true;
  }
}

verifier::TeamSnapshot TeamProgress::snapshot(double elapsed_s, const exec::MessageBook& book,
                                              const hal::TeamLink& link) const {
  verifier::TeamSnapshot snap;
  snap.elapsed_s = elapsed_s;
  for (const RobotProgress& r : robots_) {
    verifier::RobotSnapshot s;
    s.state = r.state;
    s.entered_s = r.entered_s;
    s.x_m = r.x_m;
    s.y_m = r.y_m;
    s.theta_rad = r.theta_rad;
    s.travelled_m = r.travelled_m;
    s.turned_rad = r.turned_rad;
    s.finished = r.finished;
    snap.robots.push_back(s);
  }
  for (std::size_t m = 0; m < mission_.messages.size(); ++m) {
    const mission::Message& msg = mission_.messages[m];
    bool sent = false;
    bool received = false;
    if (msg.from == self_) {
      const std::optional<std::uint64_t> seq = book.last_sent(m);
      sent = seq.has_value();
      received = sent && link.acknowledged(*seq);
    } else {
      const RobotProgress& sender = robots_.at(msg.from);
      for (const std::size_t state : notify_states(mission_.robots[msg.from], msg.name)) {
        if (state < sender.visited.size() && sender.visited[state]) {
          sent = true;
          if (sender.state != state) received = true;
        }
      }
      const bool to_self = std::find(msg.to.begin(), msg.to.end(), self_) != msg.to.end();
      if (to_self && book.received(m)) {
        sent = true;
        if (msg.to.size() == 1) received = true;
      }
    }
    snap.messages_sent.push_back(sent);
    snap.messages_received.push_back(received);
  }
  return snap;
}

}  // namespace p3at::gate
