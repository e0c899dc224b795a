#include "p3at/protocols/can/canopen.hpp"

#include <string>

namespace p3at::can {
namespace {

std::string hex_id(std::uint32_t id) {
  constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out = "0x";
  for (int shift = 8; shift >= 0; shift -= 4) out.push_back(kDigits[(id >> static_cast<unsigned>(shift)) & 0xFu]);
  return out;
}

Error wrong(const Frame& frame, const char* what, const std::string& detail) {
  return make_error(Error::Code::protocol, std::string(what) + " frame " + hex_id(frame.id) + ": " + detail);
}

Error wrong_length(const Frame& frame, const char* what, int expected) {
  return wrong(frame, what,
               "length " + std::to_string(frame.length) + " (expected " + std::to_string(expected) + ")");
}

bool is_plain_standard(const Frame& frame) { return !frame.extended && !frame.remote; }

}  // namespace

const char* to_string(MessageKind kind) {
  switch (kind) {
    case MessageKind::nmt: return "nmt";
    case MessageKind::sync: return "sync";
    case MessageKind::emcy: return "emcy";
    case MessageKind::tpdo1: return "tpdo1";
    case MessageKind::heartbeat: return "heartbeat";
    case MessageKind::other: return "other";
  }
  return "?";
}

CobId classify(const Frame& frame) {
  if (!is_plain_standard(frame)) return {};
  const std::uint32_t id = frame.id;
  if (id == kNmtCobId) return {MessageKind::nmt, 0};
  if (id == kSyncCobId) return {MessageKind::sync, 0};
  const auto node = static_cast<std::uint8_t>(id & 0x7Fu);
  if (node == 0) return {};
  switch (id & 0x780u) {
    case kEmcyBase: return {MessageKind::emcy, node};
    case kTpdo1Base: return {MessageKind::tpdo1, node};
    case kHeartbeatBase: return {MessageKind::heartbeat, node};
    default: return {};
  }
}

const char* to_string(NmtCommand command) {
  switch (command) {
    case NmtCommand::start: return "start";
    case NmtCommand::stop: return "stop";
    case NmtCommand::enter_pre_operational: return "enter-pre-operational";
    case NmtCommand::reset_node: return "reset-node";
    case NmtCommand::reset_communication: return "reset-communication";
  }
  return "?";
}

Result<Frame> encode_nmt(NmtCommand command, std::uint8_t node_id) {
  if (node_id > kMaxNodeId) {
    return make_error(Error::Code::invalid_argument,
                      "NMT node id " + std::to_string(node_id) + " (expected 0 for all, or 1-127)");
  }
  Frame frame;
  frame.id = kNmtCobId;
  frame.length = kNmtLength;
  frame.data[0] = static_cast<std::uint8_t>(command);
  frame.data[1] = node_id;
  return frame;
}

Result<NmtMessage> decode_nmt(const Frame& frame) {
  if (!is_plain_standard(frame) || frame.id != kNmtCobId) return wrong(frame, "NMT", "not COB-ID 0x000");
  if (frame.length != kNmtLength) return wrong_length(frame, "NMT", kNmtLength);
  const std::uint8_t cs = frame.data[0];
  switch (cs) {
    case 0x01:
    case 0x02:
    case 0x80:
    case 0x81:
    case 0x82: break;
    default: return wrong(frame, "NMT", "unknown command specifier " + hex_id(cs));
  }
  if (frame.data[1] > kMaxNodeId) return wrong(frame, "NMT", "node id " + std::to_string(frame.data[1]) + " > 127");
  return NmtMessage{static_cast<NmtCommand>(cs), frame.data[1]};
}

const char* to_string(NmtState state) {
  switch (state) {
    case NmtState::boot_up: return "boot-up";
    case NmtState::stopped: return "stopped";
    case NmtState::operational: return "operational";
    case NmtState::pre_operational: return "pre-operational";
  }
  return "?";
}

Frame encode_heartbeat(std::uint8_t node_id, NmtState state) {
  Frame frame;
  frame.id = heartbeat_cob_id(node_id & kMaxNodeId);
  frame.length = kHeartbeatLength;
  frame.data[0] = static_cast<std::uint8_t>(state);
  return frame;
}

Result<NmtState> decode_heartbeat(const Frame& frame) {
  if (classify(frame).kind != MessageKind::heartbeat) return wrong(frame, "heartbeat", "not a heartbeat COB-ID");
  if (frame.length != kHeartbeatLength) return wrong_length(frame, "heartbeat", kHeartbeatLength);
  switch (frame.data[0]) {
    case 0x00: return NmtState::boot_up;
    case 0x04: return NmtState::stopped;
    case 0x05: return NmtState::operational;
    case 0x7F: return NmtState::pre_operational;
    default: return wrong(frame, "heartbeat", "unknown NMT state " + hex_id(frame.data[0]));
  }
}

const char* describe_emcy_code(std::uint16_t error_code) {
  switch (error_code) {
    case emcy_code::kNoError: return "error reset";
    case emcy_code::kCanOverrun: return "CAN overrun";
    case emcy_code::kCanErrorPassive: return "CAN error passive";
    case emcy_code::kHeartbeatError: return "heartbeat error";
    case emcy_code::kRecoveredFromBusOff: return "recovered from bus-off";
    case emcy_code::kEstopCircuit: return "e-stop circuit fault";
    case emcy_code::kBumperCircuit: return "bumper circuit fault";
    default: break;
  }
  switch (error_code >> 8) {
    case 0x10: return "generic error";
    case 0x20:
    case 0x21:
    case 0x22:
    case 0x23: return "current";
    case 0x30:
    case 0x31:
    case 0x32:
    case 0x33: return "voltage";
    case 0x40:
    case 0x41:
    case 0x42: return "temperature";
    case 0x50: return "device hardware";
    case 0x60:
    case 0x61:
    case 0x62:
    case 0x63: return "device software";
    case 0x70: return "additional modules";
    case 0x80:
    case 0x81:
    case 0x82: return "communication";
    case 0x90: return "external error";
    case 0xF0: return "additional functions";
    case 0xFF: return "device specific";
    default: return "unknown error";
  }
}

Frame encode_emcy(std::uint8_t node_id, const Emergency& emergency) {
  Frame frame;
  frame.id = emcy_cob_id(node_id & kMaxNodeId);
  frame.length = kEmcyLength;
  put_le16(frame.data.data(), emergency.error_code);
  frame.data[2] = emergency.error_register;
  for (std::size_t i = 0; i < emergency.vendor.size(); ++i) frame.data[3 + i] = emergency.vendor[i];
  return frame;
}

Result<Emergency> decode_emcy(const Frame& frame) {
  if (classify(frame).kind != MessageKind::emcy) return wrong(frame, "EMCY", "not an EMCY COB-ID");
  if (frame.length != kEmcyLength) return wrong_length(frame, "EMCY", kEmcyLength);
  Emergency emergency;
  emergency.error_code = get_le16(frame.data.data());
  emergency.error_register = frame.data[2];
  for (std::size_t i = 0; i < emergency.vendor.size(); ++i) emergency.vendor[i] = frame.data[3 + i];
  return emergency;
}

}  // namespace p3at::can
