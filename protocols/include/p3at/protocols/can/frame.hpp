#pragma once
/// The portable CAN frame (classic CAN 2.0: 11- or 29-bit identifier, up to
/// 8 data bytes) and its text form, the `cansend` / `candump -L` syntax
/// (`123#DEADBEEF`, `1F334455#11.22`, `123#R`). Pure functions, no I/O.
/// Backends map this type to their OS type; only hal/socketcan knows `can_frame`.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "p3at/common/result.hpp"

namespace p3at::can {

inline constexpr std::uint32_t kMaxStandardId = 0x7FF;
inline constexpr std::uint32_t kMaxExtendedId = 0x1FFFFFFF;
inline constexpr std::size_t kMaxDataLength = 8;

/// One data or remote frame. Bytes of `data` beyond `length` are ignored
/// (and compare equal whatever they hold).
struct Frame {
  std::uint32_t id = 0;     ///< 11-bit (standard) or 29-bit (extended) identifier, no flag bits
  bool extended = false;    ///< 29-bit identifier
  bool remote = false;      ///< remote transmission request (no data, `length` is the requested DLC)
  std::uint8_t length = 0;  ///< data length code, 0..8
  std::array<std::uint8_t, kMaxDataLength> data{};

  /// The data bytes in use (empty for a remote frame).
  std::span<const std::uint8_t> payload() const {
    return {data.data(), remote ? std::size_t{0} : std::size_t{length}};
  }
};

bool operator==(const Frame& a, const Frame& b);

/// A data frame with `payload` (at most 8 bytes). An identifier out of range
/// for its format or a payload longer than 8 bytes is an invalid_argument Error.
Result<Frame> make_frame(std::uint32_t id, std::span<const std::uint8_t> payload, bool extended = false);

/// The `cansend` text of a frame: 3 hex digits for a standard id, 8 for an
/// extended one, '#', then the data as upper-case hex pairs (`R` or `R<dlc>`
/// for a remote frame). E.g. "190#40420F00A00B0700".
std::string format_frame(const Frame& frame);

/// Parses the `cansend` / `candump -L` text of a classic frame (data bytes may
/// be separated by '.'). Errors name the text and what was expected. CAN FD
/// ("##") and error frames (CAN_ERR_FLAG in an 8-digit id) are rejected.
Result<Frame> parse_frame(std::string_view text);

}  // namespace p3at::can
