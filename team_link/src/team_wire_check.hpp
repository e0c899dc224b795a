#pragma once
// Layout checks run before lcm-gen's decoders: the generated code trusts the
// lengths it reads (a negative string or array length throws or overflows),
// so every length is validated here first, against the limits of team_wire.hpp.

#include <cstddef>
#include <cstdint>
#include <span>

namespace p3at::hal::wire_check {

// Each returns true when `bytes` is exactly one message of that type (its
// LCM fingerprint, every field, nothing after) within the team link's limits.
bool notification_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint);
bool status_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint);
bool telemetry_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint);
bool verdict_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint);

}  // namespace p3at::hal::wire_check
