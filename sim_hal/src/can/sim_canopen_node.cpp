#include "p3at/sim/can/sim_canopen_node.hpp"

namespace p3at::sim {

SimCanopenNode::SimCanopenNode(std::uint8_t node_id, std::int64_t heartbeat_period_us, bool auto_start)
    : node_id_(node_id), heartbeat_period_us_(heartbeat_period_us > 0 ? heartbeat_period_us : 1), auto_start_(auto_start) {}

void SimCanopenNode::reboot() {
  booted_ = false;
  state_ = can::NmtState::pre_operational;
}

void SimCanopenNode::on_frame(const can::Frame& frame) {
  if (can::classify(frame).kind != can::MessageKind::nmt) return;
  auto nmt = can::decode_nmt(frame);
  if (!nmt || (nmt->node_id != 0 && nmt->node_id != node_id_)) return;
  switch (nmt->command) {
    case can::NmtCommand::start: state_ = can::NmtState::operational; break;
    case can::NmtCommand::stop: state_ = can::NmtState::stopped; break;
    case can::NmtCommand::enter_pre_operational: state_ = can::NmtState::pre_operational; break;
    case can::NmtCommand::reset_node:
    case can::NmtCommand::reset_communication: reboot(); break;
  }
}

Status SimCanopenNode::step(hal::CanBus& bus, std::int64_t now_us) {
  if (silent_) return {};
  if (!booted_) {
    booted_ = true;
    ++generation_;
    state_ = auto_start_ ? can::NmtState::operational : can::NmtState::pre_operational;
    next_heartbeat_us_ = now_us + heartbeat_period_us_;
    return bus.send(can::encode_heartbeat(node_id_, can::NmtState::boot_up));
  }
  if (now_us < next_heartbeat_us_) return {};
  // One heartbeat however late we are: a heartbeat reports the present, it is not a sample series.
  while (next_heartbeat_us_ <= now_us) next_heartbeat_us_ += heartbeat_period_us_;
  return bus.send(can::encode_heartbeat(node_id_, state_));
}

}  // namespace p3at::sim
