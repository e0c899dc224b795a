#include "p3at/bridge/accessories/guarded_drive_base.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace p3at::bridge {

GuardedDriveBase::GuardedDriveBase(hal::DriveBase& inner, AccessoryHub& hub, hal::Clock& clock,
                                   ReenableMotors reenable, GuardConfig config)
    : inner_(inner), hub_(hub), clock_(clock), reenable_(std::move(reenable)), config_(std::move(config)) {
  verdict_.why = "not armed yet";
  refresh_state();
}

const SafetyVerdict& GuardedDriveBase::check() {
  const std::int64_t now_us = clock_.now_us();
  verdict_ = hub_.poll(now_us);
  if (verdict_.stop_now) {
    // Stop first, report after: the emergency stop must not wait for anything.
    const Status st = inner_.emergency_stop();
    ++emergency_stops_;
    last_stop_us_ = now_us;
    if (config_.log) {
      std::fprintf(stderr, "[%s] event=emergency-stop why=\"%s\" estop_sent=%s\n", config_.log_name.c_str(),
                   verdict_.why.c_str(), st ? "yes" : st.error().message.c_str());
    }
  }
  refresh_state();
  return verdict_;
}

Result<bool> GuardedDriveBase::wait_for_update(int timeout_ms) {
  const std::int64_t deadline_us = clock_.now_us() + static_cast<std::int64_t>(std::max(timeout_ms, 0)) * 1000;
  for (;;) {
    check();
    const std::int64_t left_us = deadline_us - clock_.now_us();
    const int slice_ms =
        static_cast<int>(std::clamp<std::int64_t>((left_us + 999) / 1000, 0, config_.poll_slice_ms));
    auto got = inner_.wait_for_update(slice_ms);
    if (!got) {
      refresh_state();
      return got;
    }
    if (*got) {
      hub_.observe(inner_.state());
      check();
      return true;
    }
    if (clock_.now_us() >= deadline_us) {
      check();
      return false;
    }
  }
}

Status GuardedDriveBase::set_velocity(double trans_mps, double rot_radps) {
  check();
  if (!verdict_.motion_allowed) {
    return make_error(Error::Code::state, "motion refused by the safety latch: " + verdict_.why);
  }
  return inner_.set_velocity(trans_mps, rot_radps);
}

Status GuardedDriveBase::rearm() {
  check();
  if (auto st = hub_.rearm(clock_.now_us()); !st) return st;
  if (reenable_) {
    // The latch is armed but the motors are not on (ArcosClient: ENABLE lost five
    // times, or the robot's e-stop pressed): the inner base keeps refusing motion.
    if (auto st = reenable_(); !st) {
      return make_error(st.error().code, "motors not re-enabled: " + st.error().message);
    }
  }
  check();
  if (config_.log) std::fprintf(stderr, "[%s] event=re-armed\n", config_.log_name.c_str());
  return {};
}

void GuardedDriveBase::refresh_state() {
  const hal::DriveState& inner = inner_.state();
  const bool new_update = !have_update_ || inner.update_count != seen_update_;
  state_ = inner;
  if (config_.gyro_aided_pose && inner.update_count > 0) {
    if (new_update) aided_ = hub_.aided_pose(inner.odometry, inner.stamp_us);
    state_.odometry = aided_;
  }
  have_update_ = true;
  seen_update_ = inner.update_count;
  if (state_.link == hal::LinkState::ok && !verdict_.motion_allowed) {
    state_.link = hal::LinkState::safety_stop;
    state_.why_stopped = verdict_.why;
  }
}

}  // namespace p3at::bridge
