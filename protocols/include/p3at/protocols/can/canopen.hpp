#pragma once
/// The CANopen (CiA 301) messages our accessory bus uses: the predefined
/// connection set's COB-IDs, NMT node control, heartbeat and EMCY. Device
/// payloads (TPDO1 of the gyro and of the safety node) are in accessories.hpp.
/// Layouts and rationale: docs/can-bus.md. Pure functions, no I/O.

#include <array>
#include <cstdint>

#include "p3at/common/result.hpp"
#include "p3at/protocols/can/frame.hpp"

namespace p3at::can {

/// CANopen node ids are 1..127; 0 in an NMT command addresses every node.
inline constexpr std::uint8_t kMinNodeId = 1;
inline constexpr std::uint8_t kMaxNodeId = 127;

/// Function codes of the predefined connection set (COB-ID = base + node id).
inline constexpr std::uint32_t kNmtCobId = 0x000;
inline constexpr std::uint32_t kSyncCobId = 0x080;
inline constexpr std::uint32_t kEmcyBase = 0x080;
inline constexpr std::uint32_t kTpdo1Base = 0x180;
inline constexpr std::uint32_t kHeartbeatBase = 0x700;

/// What a standard-id frame is, by its COB-ID.
enum class MessageKind {
  nmt,        ///< 0x000
  sync,       ///< 0x080
  emcy,       ///< 0x081..0x0FF
  tpdo1,      ///< 0x181..0x1FF
  heartbeat,  ///< 0x701..0x77F
  other,      ///< any other COB-ID, an extended id or a remote frame
};

const char* to_string(MessageKind kind);

struct CobId {
  MessageKind kind = MessageKind::other;
  std::uint8_t node_id = 0;  ///< 1..127 for emcy/tpdo1/heartbeat, 0 otherwise
};

/// Classifies a frame by its identifier (its length is not checked here).
CobId classify(const Frame& frame);

constexpr std::uint32_t emcy_cob_id(std::uint8_t node_id) { return kEmcyBase + node_id; }
constexpr std::uint32_t tpdo1_cob_id(std::uint8_t node_id) { return kTpdo1Base + node_id; }
constexpr std::uint32_t heartbeat_cob_id(std::uint8_t node_id) { return kHeartbeatBase + node_id; }
constexpr bool valid_node_id(int node_id) { return node_id >= kMinNodeId && node_id <= kMaxNodeId; }

// ---- NMT node control (master → nodes), 2 bytes: command specifier, node id ----

inline constexpr std::uint8_t kNmtLength = 2;

enum class NmtCommand : std::uint8_t {
  start = 0x01,                ///< enter operational (PDOs flow)
  stop = 0x02,                 ///< enter stopped (heartbeat only)
  enter_pre_operational = 0x80,
  reset_node = 0x81,
  reset_communication = 0x82,
};

const char* to_string(NmtCommand command);

struct NmtMessage {
  NmtCommand command = NmtCommand::start;
  std::uint8_t node_id = 0;  ///< 0 = all nodes
};

/// An NMT frame. A node id above 127 is an invalid_argument Error.
Result<Frame> encode_nmt(NmtCommand command, std::uint8_t node_id);
/// Errors: not COB-ID 0, length other than 2, unknown command specifier, node id > 127.
Result<NmtMessage> decode_nmt(const Frame& frame);

// ---- Heartbeat (node → all), 1 byte: NMT state ----

inline constexpr std::uint8_t kHeartbeatLength = 1;

enum class NmtState : std::uint8_t {
  boot_up = 0x00,  ///< sent once after (re)start
  stopped = 0x04,
  operational = 0x05,
  pre_operational = 0x7F,
};

const char* to_string(NmtState state);

Frame encode_heartbeat(std::uint8_t node_id, NmtState state);
/// Errors: not a heartbeat COB-ID, length other than 1, unknown state
/// (bit 7, the node-guarding toggle, must be 0 in a heartbeat).
Result<NmtState> decode_heartbeat(const Frame& frame);

// ---- EMCY (node → all), 8 bytes: error code (u16 LE), error register, 5 vendor bytes ----

inline constexpr std::uint8_t kEmcyLength = 8;

/// CiA 301 emergency error codes used on our bus (docs/can-bus.md lists them).
namespace emcy_code {
inline constexpr std::uint16_t kNoError = 0x0000;            ///< error reset: the node's faults cleared
inline constexpr std::uint16_t kGeneric = 0x1000;
inline constexpr std::uint16_t kDeviceTemperature = 0x4200;  ///< gyro above its operating temperature
inline constexpr std::uint16_t kDeviceHardware = 0x5000;     ///< sensor or circuit failure
inline constexpr std::uint16_t kDeviceSoftware = 0x6100;
inline constexpr std::uint16_t kCanOverrun = 0x8110;
inline constexpr std::uint16_t kCanErrorPassive = 0x8120;
inline constexpr std::uint16_t kHeartbeatError = 0x8130;     ///< a node missed the master's heartbeat
inline constexpr std::uint16_t kRecoveredFromBusOff = 0x8140;
inline constexpr std::uint16_t kEstopCircuit = 0xFF01;       ///< safety node: e-stop channels disagree
inline constexpr std::uint16_t kBumperCircuit = 0xFF02;      ///< safety node: bumper loop open
}  // namespace emcy_code

/// Error register (object 0x1001) bits.
namespace error_register {
inline constexpr std::uint8_t kGeneric = 0x01;
inline constexpr std::uint8_t kTemperature = 0x08;
inline constexpr std::uint8_t kCommunication = 0x10;
inline constexpr std::uint8_t kManufacturer = 0x80;
}  // namespace error_register

struct Emergency {
  std::uint16_t error_code = emcy_code::kNoError;
  std::uint8_t error_register = 0;
  std::array<std::uint8_t, 5> vendor{};  ///< manufacturer-specific bytes
};

/// Short description of an error code for logs ("device temperature", "e-stop circuit", …),
/// by exact code first, then by CiA 301 class (upper byte).
const char* describe_emcy_code(std::uint16_t error_code);

Frame encode_emcy(std::uint8_t node_id, const Emergency& emergency);
/// Errors: not an EMCY COB-ID, length other than 8.
Result<Emergency> decode_emcy(const Frame& frame);

// ---- little-endian helpers for payloads ----

inline void put_le16(std::uint8_t* out, std::uint16_t v) {
  out[0] = static_cast<std::uint8_t>(v & 0xFFu);
  out[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void put_le32(std::uint8_t* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFFu);
}
inline std::uint16_t get_le16(const std::uint8_t* in) {
  return static_cast<std::uint16_t>(in[0] | (in[1] << 8));
}
inline std::uint32_t get_le32(const std::uint8_t* in) {
  return static_cast<std::uint32_t>(in[0]) | (static_cast<std::uint32_t>(in[1]) << 8) |
         (static_cast<std::uint32_t>(in[2]) << 16) | (static_cast<std::uint32_t>(in[3]) << 24);
}

}  // namespace p3at::can
