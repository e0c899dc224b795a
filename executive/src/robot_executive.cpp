#include "p3at/executive/robot_executive.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "p3at/common/log.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/executive/frames.hpp"
#include "p3at/executive/sonar.hpp"

namespace p3at::exec {
namespace {

constexpr const char* kLog = "executive";
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;

std::string seconds(double t_s) { return format_fixed(t_s, 3); }

std::optional<std::string> trigger_message(const mission::TriggerParams& trigger) {
  if (const auto* n = std::get_if<mission::NotifiedParams>(&trigger)) return n->message;
  if (const auto* m = std::get_if<mission::MessageSentParams>(&trigger)) return m->message;
  return std::nullopt;
}

}  // namespace

const char* to_string(Phase phase) {
  switch (phase) {
    case Phase::running: return "running";
    case Phase::finished: return "finished";
    case Phase::aborted: return "aborted";
  }
  return "?";
}

RobotExecutive::RobotExecutive(const mission::Mission& mission, std::size_t robot_index, hal::DriveBase& drive,
                               hal::TeamLink& team_link, hal::Clock& clock, ExecutiveOptions options)
    : mission_(mission),
      robot_index_(robot_index),
      drive_(drive),
      team_link_(team_link),
      clock_(clock),
      options_(std::move(options)),
      messages_(mission.messages.size()),
      noise_(options_.seed, robot_index < mission.robots.size() ? mission.robots[robot_index].name : std::string()),
      stats_(options_.period_us) {
  validate();
  const mission::RobotSpec& spec = robot();
  behavior_config_.max_speed_mps = spec.max_speed_mps;
  behavior_config_.max_rot_radps = options_.max_rot_radps;
  behavior_config_.rot_gain = options_.rot_gain;
  behavior_config_.robot_radius_m = options_.robot_radius_m;
  for (const mission::Transition& t : spec.transitions) {
    const std::optional<std::string> name = trigger_message(t.trigger);
    transition_message_.push_back(name ? mission_.find_message(*name) : std::nullopt);
  }
  for (const mission::State& s : spec.states) {
    const auto* notify = std::get_if<mission::NotifyParams>(&s.behavior);
    state_message_.push_back(notify ? mission_.find_message(notify->message) : std::nullopt);
  }
  current_ = spec.initial;
  pose_ = Pose<double>{spec.start.x_m, spec.start.y_m, spec.start.theta_deg * kDegToRad};
  inbox_.reserve(16);
}

void RobotExecutive::validate() const {
  if (robot_index_ >= mission_.robots.size()) {
    throw std::invalid_argument("robot index " + std::to_string(robot_index_) + " out of range: mission '" +
                                mission_.name + "' has " + std::to_string(mission_.robots.size()) + " robots");
  }
  const mission::RobotSpec& spec = robot();
  const std::string who = "mission '" + mission_.name + "' robot '" + spec.name + "': ";
  if (spec.states.empty()) throw std::invalid_argument(who + "has no states");
  if (spec.initial >= spec.states.size()) throw std::invalid_argument(who + "initial state index out of range");
  for (std::size_t i = 0; i < spec.transitions.size(); ++i) {
    const mission::Transition& t = spec.transitions[i];
    if (t.from >= spec.states.size() || t.to >= spec.states.size()) {
      throw std::invalid_argument(who + "transition " + std::to_string(i) + " names a state out of range");
    }
    if (const std::optional<std::string> name = trigger_message(t.trigger); name && !mission_.find_message(*name)) {
      throw std::invalid_argument(who + "transition " + std::to_string(i) + " waits for undeclared message '" +
                                  *name + "'");
    }
  }
  for (const mission::State& s : spec.states) {
    for (const std::size_t t : s.outgoing) {
      if (t >= spec.transitions.size()) throw std::invalid_argument(who + "state '" + s.name + "' lists a bad transition");
    }
    if (const auto* notify = std::get_if<mission::NotifyParams>(&s.behavior)) {
      const std::optional<std::size_t> m = mission_.find_message(notify->message);
      if (!m) throw std::invalid_argument(who + "state '" + s.name + "' notifies undeclared message '" + notify->message + "'");
      for (const std::size_t to : mission_.messages[*m].to) {
        if (to >= mission_.robots.size()) throw std::invalid_argument(who + "message '" + notify->message + "' has a bad recipient");
      }
    }
  }
  for (const mission::Message& m : mission_.messages) {
    if (m.from >= mission_.robots.size()) throw std::invalid_argument("message '" + m.name + "' has a bad sender");
  }
}

const std::string& RobotExecutive::state_name() const { return robot().states[current_].name; }

double RobotExecutive::elapsed_s() const {
  if (!started_) return 0.0;
  const std::int64_t until_us = end_us_ ? *end_us_ : now_us_;
  return static_cast<double>(until_us - start_us_) / 1e6;
}

bool RobotExecutive::team_settled() const {
  const std::vector<hal::TeamStatus>& statuses = team_link_.teammate_status();
  for (std::size_t i = 0; i < mission_.robots.size(); ++i) {
    if (i == robot_index_) continue;
    const std::string& name = mission_.robots[i].name;
    const auto it = std::find_if(statuses.begin(), statuses.end(),
                                 [&](const hal::TeamStatus& s) { return s.robot == name; });
    if (it == statuses.end() || (it->phase != "finished" && it->phase != "aborted")) return false;
  }
  return true;
}

std::string RobotExecutive::pose_fields() const {
  return "x_m=" + format_fixed(pose_.x_m, 3) + " y_m=" + format_fixed(pose_.y_m, 3) + " th_deg=" + format_fixed(pose_.theta_rad * kRadToDeg, 1);
}

// ------------------------------------------------------------------ the cycle

void RobotExecutive::cycle() {
  const auto compute_start = std::chrono::steady_clock::now();
  const std::int64_t now_us = clock_.now_us();
  const hal::DriveState& state = drive_.state();
  const bool missed_update = started_ && state.update_count == last_update_count_;
  last_update_count_ = state.update_count;
  ++cycle_count_;
  status_published_this_cycle_ = false;
  now_us_ = now_us;

  if (!started_) {
    start(now_us, state);
  } else {
    update_pose(state);
  }
  poll_team(now_us);
  if (running() && check_safety(state)) {
    if (!entered_initial_) {
      entered_initial_ = true;
      log::info(kLog, "event=start robot=" + robot().name + " mission=" + mission_.name + " state=" +
                          robot().states[current_].name + " " + pose_fields());
      enter_state(current_);
    } else {
      evaluate_transitions();
    }
    if (running()) command_motion(state);
  }

  if (options_.telemetry_every_cycles != 0 && cycle_count_ % options_.telemetry_every_cycles == 0) {
    publish_telemetry(state);
  }
  if (!status_published_this_cycle_ && options_.status_every_cycles != 0 &&
      cycle_count_ % options_.status_every_cycles == 0) {
    publish_status();
  }
  const std::chrono::duration<double, std::micro> compute = std::chrono::steady_clock::now() - compute_start;
  stats_.record(compute.count(), missed_update);
}

void RobotExecutive::start(std::int64_t now_us, const hal::DriveState& state) {
  started_ = true;
  start_us_ = now_us;
  // The robot stands at its start pose now: odometry from here on is relative to this reading.
  odometry_origin_ = state.odometry;
  const mission::Pose2& s = robot().start;
  pose_ = Pose<double>{s.x_m, s.y_m, s.theta_deg * kDegToRad};
}

void RobotExecutive::update_pose(const hal::DriveState& state) {
  const Pose<double> origin{odometry_origin_.x_m, odometry_origin_.y_m, odometry_origin_.theta_rad};
  const Pose<double> odometry{state.odometry.x_m, state.odometry.y_m, state.odometry.theta_rad};
  const mission::Pose2& s = robot().start;
  const Pose<double> start{s.x_m, s.y_m, s.theta_deg * kDegToRad};
  const Pose<double> next = compose(start, relative(origin, odometry));
  // The odometry heading is continuous; wrapping the step guards against a source that is not.
  turned_rad_ += std::abs(wrap_angle_rad(next.theta_rad - pose_.theta_rad));
  pose_ = next;
}

void RobotExecutive::poll_team(std::int64_t now_us) {
  inbox_.clear();
  if (const Status st = team_link_.poll(now_us, inbox_); !st) {
    // Transport trouble is retried by the link itself (retransmissions); report, do not abort.
    if (poll_errors_++ % 50 == 0) {
      log::warn(kLog, "event=team-poll-error robot=" + robot().name + " count=" + std::to_string(poll_errors_) +
                          " error=\"" + st.error().message + "\"");
    }
  }
  for (const hal::TeamNotification& n : inbox_) {
    const std::optional<std::size_t> index = mission_.find_message(n.message);
    if (!index) {
      log::warn(kLog, "event=notification-ignored robot=" + robot().name + " message=" + n.message + " from=" +
                          n.sender + " why=undeclared");
      continue;
    }
    const mission::Message& m = mission_.messages[*index];
    if (mission_.robots[m.from].name != n.sender) {
      log::warn(kLog, "event=notification-ignored robot=" + robot().name + " message=" + n.message + " from=" +
                          n.sender + " why=wrong-sender");
      continue;
    }
    if (std::find(m.to.begin(), m.to.end(), robot_index_) == m.to.end()) continue;  // overheard, not ours
    if (messages_.mark_received(*index)) {
      log::info(kLog, "event=notified robot=" + robot().name + " t_s=" + seconds(elapsed_s()) + " message=" +
                          n.message + " from=" + n.sender + " seq=" + std::to_string(n.seq));
    }
  }
  if (running()) {
    for (const hal::TeamStatus& s : team_link_.teammate_status()) {
      if (s.robot != robot().name && s.phase == "aborted") {
        abort_now("teammate " + s.robot + " aborted" + (s.reason.empty() ? std::string() : ": " + s.reason));
        break;
      }
    }
  }
}

bool RobotExecutive::check_safety(const hal::DriveState& state) {
  if (state.link == hal::LinkState::ok) return true;
  std::string reason = state.link == hal::LinkState::safety_stop ? "safety stop" : "drive link ";
  if (state.link != hal::LinkState::safety_stop) reason += hal::to_string(state.link);
  if (!state.why_stopped.empty()) reason += ": " + state.why_stopped;
  abort_now(reason);
  return false;
}

void RobotExecutive::evaluate_transitions() {
  const mission::RobotSpec& spec = robot();
  const TriggerInputs inputs{pose_, turned_rad_, &messages_, &team_link_};
  for (const std::size_t t : spec.states[current_].outgoing) {
    const mission::Transition& transition = spec.transitions[t];
    if (!trigger_holds(transition.trigger, transition_message_[t], inputs)) continue;
    ++transition_count_;
    const double t_s = elapsed_s();
    log::info(kLog, "event=transition robot=" + spec.name + " t_s=" + seconds(t_s) + " from=" +
                        spec.states[transition.from].name + " to=" + spec.states[transition.to].name +
                        " cause=" + std::string(mission::to_string(transition.kind())) + " " + pose_fields());
    if (options_.on_transition) {
      options_.on_transition(TransitionEvent{robot_index_, t_s, transition.from, transition.to, transition.kind(), pose_});
    }
    enter_state(transition.to);
    return;  // at most one transition per cycle
  }
}

void RobotExecutive::enter_state(std::size_t index) {
  current_ = index;
  turned_rad_ = 0.0;
  const mission::State& s = robot().states[index];
  std::visit(
      [&](const auto& params) {
        using T = std::decay_t<decltype(params)>;
        if constexpr (std::is_same_v<T, mission::GoToGuardedParams>) {
          noise_.restart();
        } else if constexpr (std::is_same_v<T, mission::SpinParams>) {
          if (std::abs(params.rate_deg_s * kDegToRad) > behavior_config_.max_rot_radps) {
            log::warn(kLog, "event=spin-limited robot=" + robot().name + " state=" + s.name + " rate_deg_s=" +
                                format_fixed(params.rate_deg_s, 1) + " max_deg_s=" +
                                format_fixed(behavior_config_.max_rot_radps * kRadToDeg, 1));
          }
        } else if constexpr (std::is_same_v<T, mission::NotifyParams>) {
          send_notification(params);
        } else {
          static_assert(std::is_same_v<T, mission::StopParams>);
        }
      },
      s.behavior);
  if (!running()) return;
  if (robot().is_final(index)) {
    finish();
  } else {
    publish_status();
  }
}

void RobotExecutive::send_notification(const mission::NotifyParams& params) {
  const std::size_t index = *state_message_[current_];  // resolved in validate()
  const mission::Message& m = mission_.messages[index];
  std::vector<std::string> recipients;
  std::string to_list;
  for (const std::size_t r : m.to) {
    recipients.push_back(mission_.robots[r].name);
    to_list += (to_list.empty() ? "" : ",") + mission_.robots[r].name;
  }
  const Result<std::uint64_t> seq = team_link_.notify(params.message, recipients);
  if (!seq) {
    abort_now("cannot notify " + params.message + ": " + seq.error().message);
    return;
  }
  messages_.record_sent(index, *seq);
  log::info(kLog, "event=notify robot=" + robot().name + " t_s=" + seconds(elapsed_s()) + " message=" +
                      params.message + " seq=" + std::to_string(*seq) + " to=" + to_list);
}

void RobotExecutive::command_motion(const hal::DriveState& state) {
  const mission::State& s = robot().states[current_];
  Velocity<double> command{0.0, 0.0};
  if (const auto* go = std::get_if<mission::GoToGuardedParams>(&s.behavior)) {
    const SonarObstacles<double> obstacles =
        sonar_obstacles(std::span<const double, kP3atSonarCount>(state.sonar_m), pose_, options_.sonar_max_range_m);
    const Vec2<double> noise_direction = noise_.next(go->noise_persistence_cycles);
    command = go_to_guarded(*go, pose_, obstacles.view(), noise_direction, behavior_config_);
  } else if (const auto* spin = std::get_if<mission::SpinParams>(&s.behavior)) {
    command = spin_command(*spin, behavior_config_);
  }
  last_command_ = command;
  if (const Status st = drive_.set_velocity(command.trans_mps, command.rot_radps); !st) {
    abort_now("motion command refused: " + st.error().message);
  }
}

void RobotExecutive::finish() {
  outcome_ = Outcome{Phase::finished, {}};
  end_us_ = now_us_;
  last_command_ = Velocity<double>{0.0, 0.0};
  if (const Status st = drive_.stop(); !st) {
    log::warn(kLog, "event=stop-failed robot=" + robot().name + " error=\"" + st.error().message + "\"");
  }
  log::info(kLog, "event=phase robot=" + robot().name + " phase=finished t_s=" + seconds(elapsed_s()) + " state=" +
                      state_name() + " " + pose_fields());
  publish_status();
}

void RobotExecutive::abort(const std::string& reason) {
  if (!running()) return;
  if (!started_) {
    now_us_ = clock_.now_us();
    start(now_us_, drive_.state());
  }
  abort_now(reason);
}

void RobotExecutive::abort_now(const std::string& reason) {
  outcome_ = Outcome{Phase::aborted, reason};
  end_us_ = now_us_;
  last_command_ = Velocity<double>{0.0, 0.0};
  // stop(), never emergency_stop(): on a lost link neither reaches the robot (its
  // firmware watchdog halts it), and an emergency stop would latch and disable the
  // motors, which the bridge would then refuse to undo without an operator.
  if (const Status st = drive_.stop(); !st) {
    log::warn(kLog, "event=stop-failed robot=" + robot().name + " error=\"" + st.error().message + "\"");
  }
  log::warn(kLog, "event=phase robot=" + robot().name + " phase=aborted t_s=" + seconds(elapsed_s()) + " state=" +
                      state_name() + " " + pose_fields() + " reason=\"" + reason + "\"");
  publish_status();
}

void RobotExecutive::publish_status() {
  status_published_this_cycle_ = true;
  hal::TeamStatus status;
  status.robot = robot().name;
  status.phase = to_string(outcome_.phase);
  status.state = state_name();
  status.reason = outcome_.reason;
  status.p_success = options_.p_success;
  if (const Status st = team_link_.publish_status(status); !st && publish_errors_++ % 50 == 0) {
    log::warn(kLog, "event=publish-error robot=" + robot().name + " what=status error=\"" + st.error().message + "\"");
  }
}

void RobotExecutive::publish_telemetry(const hal::DriveState& state) {
  hal::Telemetry t;
  t.robot = robot().name;
  t.state = state_name();
  t.x_m = pose_.x_m;
  t.y_m = pose_.y_m;
  t.theta_rad = pose_.theta_rad;
  t.trans_vel_mps = state.trans_vel_mps;
  t.rot_vel_radps = state.rot_vel_radps;
  t.cycles = stats_.cycles();
  t.overruns = stats_.overruns();
  t.missed_updates = stats_.missed_updates();
  t.cycle_p50_us = stats_.p50_us();
  t.cycle_p99_us = stats_.p99_us();
  if (const Status st = team_link_.publish_telemetry(t); !st && publish_errors_++ % 50 == 0) {
    log::warn(kLog, "event=publish-error robot=" + robot().name + " what=telemetry error=\"" + st.error().message + "\"");
  }
}

}  // namespace p3at::exec
