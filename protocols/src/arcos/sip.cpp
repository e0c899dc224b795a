#include "p3at/protocols/arcos/sip.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "byte_io.hpp"
#include "p3at/protocols/arcos/commands.hpp"

namespace p3at::arcos {

namespace {

// Mandatory SIP payload, from XPOS up to and including the sonar count byte.
constexpr std::size_t kSipMandatoryBytes = 19;
constexpr std::size_t kSonarEntryBytes = 3;
// Three strings plus terminators always fit in one payload.
constexpr std::size_t kMaxIdentityString = 80;

}  // namespace

bool Sip::operator==(const Sip& other) const {
  // Sonar entries past sonar_count are unused and not compared.
  const std::size_t n = std::min<std::size_t>(sonar_count, sonar.size());
  return moving == other.moving && xpos == other.xpos && ypos == other.ypos && thpos == other.thpos &&
         left_vel == other.left_vel && right_vel == other.right_vel && battery == other.battery &&
         stall_bumpers == other.stall_bumpers && control == other.control && flags == other.flags &&
         compass == other.compass && sonar_count == other.sonar_count &&
         std::equal(sonar.begin(), sonar.begin() + static_cast<std::ptrdiff_t>(n), other.sonar.begin(),
                    [](const SonarRaw& a, const SonarRaw& b) { return a.number == b.number && a.range == b.range; }) &&
         io == other.io && battery_x10 == other.battery_x10 && charge_state == other.charge_state &&
         rotvel == other.rotvel && fault_flags == other.fault_flags && latvel == other.latvel &&
         temperature == other.temperature && state_of_charge == other.state_of_charge &&
         controller_time_us == other.controller_time_us && flags3 == other.flags3;
}

Frame encode_sip(const Sip& sip) {
  detail::PayloadWriter w;
  w.u16(sip.xpos);
  w.u16(sip.ypos);
  w.s16(sip.thpos);
  w.s16(sip.left_vel);
  w.s16(sip.right_vel);
  w.u8(sip.battery);
  w.u16(sip.stall_bumpers);
  w.s16(sip.control);
  w.u16(sip.flags);
  w.u8(sip.compass);
  const auto n = static_cast<std::uint8_t>(std::min<std::size_t>(sip.sonar_count, sip.sonar.size()));
  w.u8(n);
  for (std::size_t i = 0; i < n; ++i) {
    w.u8(sip.sonar[i].number);
    w.u16(sip.sonar[i].range);
  }
  // Optional groups: a prefix, up to the first absent one.
  [&] {
    if (!sip.io) return;
    w.u8(sip.io->grip_state);
    w.u8(sip.io->anport);
    w.u8(sip.io->analog);
    w.u8(sip.io->digin);
    w.u8(sip.io->digout);
    if (!sip.battery_x10) return;
    w.u16(*sip.battery_x10);
    if (!sip.charge_state) return;
    w.u8(*sip.charge_state);
    if (!sip.rotvel) return;
    w.s16(*sip.rotvel);
    if (!sip.fault_flags) return;
    w.u16(*sip.fault_flags);
    if (!sip.latvel) return;
    w.s16(*sip.latvel);
    if (!sip.temperature) return;
    w.s8(*sip.temperature);
    if (!sip.state_of_charge) return;
    w.u8(*sip.state_of_charge);
    if (!sip.controller_time_us) return;
    w.u32(*sip.controller_time_us);
    if (!sip.flags3) return;
    w.u32(*sip.flags3);
  }();
  return encode_frame(sip.moving ? kSipMoving : kSipStopped, w.bytes());
}

namespace {

template <class T, class Read>
bool read_optional(std::optional<T>& out, Read&& read) {
  T value{};
  if (!read(value)) return false;
  out = value;
  return true;
}

}  // namespace

Result<Sip> decode_sip(const Packet& packet) {
  if (packet.id != kSipStopped && packet.id != kSipMoving) {
    return make_error(Error::Code::protocol,
                      "SIP: packet type " + std::to_string(packet.id) + " is not 0x32 or 0x33");
  }
  const auto payload = packet.payload();
  if (payload.size() < kSipMandatoryBytes) {
    return make_error(Error::Code::protocol, "SIP: payload of " + std::to_string(payload.size()) +
                                                 " bytes is shorter than the " +
                                                 std::to_string(kSipMandatoryBytes) + " mandatory bytes");
  }
  Sip sip;
  sip.moving = packet.id == kSipMoving;
  detail::PayloadReader r(payload);
  // Lengths were checked above, so these reads cannot fail.
  (void)r.u16(sip.xpos);
  (void)r.u16(sip.ypos);
  (void)r.s16(sip.thpos);
  (void)r.s16(sip.left_vel);
  (void)r.s16(sip.right_vel);
  (void)r.u8(sip.battery);
  (void)r.u16(sip.stall_bumpers);
  (void)r.s16(sip.control);
  (void)r.u16(sip.flags);
  (void)r.u8(sip.compass);
  (void)r.u8(sip.sonar_count);
  if (sip.sonar_count > sip.sonar.size()) {
    return make_error(Error::Code::protocol, "SIP: sonar count " + std::to_string(sip.sonar_count) +
                                                 " exceeds the " + std::to_string(sip.sonar.size()) +
                                                 " readings a SIP can hold");
  }
  if (r.remaining() < std::size_t{sip.sonar_count} * kSonarEntryBytes) {
    return make_error(Error::Code::protocol, "SIP: sonar block of " + std::to_string(sip.sonar_count) +
                                                 " readings needs " +
                                                 std::to_string(std::size_t{sip.sonar_count} * kSonarEntryBytes) +
                                                 " bytes, only " + std::to_string(r.remaining()) + " remain");
  }
  for (std::size_t i = 0; i < sip.sonar_count; ++i) {
    (void)r.u8(sip.sonar[i].number);
    (void)r.u16(sip.sonar[i].range);
  }
  // Each optional group is read only if it is whole and all groups before it were.
  [&] {
    if (r.remaining() < 5) return;
    SipIo io;
    (void)r.u8(io.grip_state);
    (void)r.u8(io.anport);
    (void)r.u8(io.analog);
    (void)r.u8(io.digin);
    (void)r.u8(io.digout);
    sip.io = io;
    if (!read_optional(sip.battery_x10, [&](std::uint16_t& v) { return r.u16(v); })) return;
    if (!read_optional(sip.charge_state, [&](std::uint8_t& v) { return r.u8(v); })) return;
    if (!read_optional(sip.rotvel, [&](std::int16_t& v) { return r.s16(v); })) return;
    if (!read_optional(sip.fault_flags, [&](std::uint16_t& v) { return r.u16(v); })) return;
    if (!read_optional(sip.latvel, [&](std::int16_t& v) { return r.s16(v); })) return;
    if (!read_optional(sip.temperature, [&](std::int8_t& v) { return r.s8(v); })) return;
    if (!read_optional(sip.state_of_charge, [&](std::uint8_t& v) { return r.u8(v); })) return;
    if (!read_optional(sip.controller_time_us, [&](std::uint32_t& v) { return r.u32(v); })) return;
    (void)read_optional(sip.flags3, [&](std::uint32_t& v) { return r.u32(v); });
  }();
  return sip;
}

Frame encode_identity(const RobotIdentity& identity) {
  detail::PayloadWriter w;
  w.cstring(identity.name, kMaxIdentityString);
  w.cstring(identity.robot_class, kMaxIdentityString);
  w.cstring(identity.subclass, kMaxIdentityString);
  return encode_frame(kSync2, w.bytes());
}

RobotIdentity decode_identity(const Packet& packet) {
  RobotIdentity identity;
  detail::PayloadReader r(packet.payload());
  (void)r.cstring(identity.name);
  (void)r.cstring(identity.robot_class);
  (void)r.cstring(identity.subclass);
  return identity;
}

int wrap_delta_15bit(std::uint16_t previous, std::uint16_t current) {
  int delta = (current & 0x7FFF) - (previous & 0x7FFF);
  if (delta > 0x1000) {
    delta -= 0x8000;
  } else if (delta < -0x1000) {
    delta += 0x8000;
  }
  return delta;
}

int wrap_delta_heading(std::int16_t previous, std::int16_t current) {
  int delta = (int{current} - int{previous}) % 4096;
  if (delta < 0) delta += 4096;
  if (delta > 2048) delta -= 4096;
  return delta;
}

RobotParams RobotParams::for_subclass(const std::string& subclass) {
  std::string lower(subclass);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
  RobotParams params;
  if (lower == "p3at") params.dist_conv = 0.465;
  return params;
}

}  // namespace p3at::arcos
