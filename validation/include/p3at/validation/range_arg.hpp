#pragma once
// The A:B:STEP axis syntax of `vipars validate` and `vipars verify`
// (--tmax-range, --rmax-range): A, A+STEP, A+2·STEP, ... up to B, and B
// itself when (B-A)/STEP is an integer within 1e-9 (so 1:3:0.1 ends at 3
// although 0.1 is not exact in binary).

#include <cstddef>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"

namespace p3at::vipars {

/// At most this many values per axis: a typo like 0:200:0.00001 is refused
/// rather than running out of memory.
inline constexpr std::size_t kMaxRangeValues = 100'000;

/// Parses "A:B:STEP" (decimal numbers, B >= A, STEP > 0, all finite).
/// Values are A + k·STEP, each rounded to 15 significant digits so that
/// 1:3:0.1 gives 1.7 rather than 1.7000000000000002; the first is exactly
/// A and, when included, the last exactly B. On error the message
/// says what was expected, e.g. "expected A:B:STEP with STEP > 0, got '1:3:0'".
Result<std::vector<double>> parse_range(std::string_view text);

}  // namespace p3at::vipars
