#pragma once
/// Text laid out in columns, as printf's "%-*s" and "%*s" did, without a
/// fixed buffer: a text longer than its column is kept whole (the column
/// widens), never cut. Widths count bytes, as printf's do. Numbers in the
/// columns come from number_format.hpp.

#include <cstddef>
#include <string>
#include <string_view>

namespace p3at {

/// printf("%-*s", width, text): `text`, then spaces up to `width` bytes.
inline std::string left_aligned(std::string_view text, std::size_t width) {
  std::string out(text);
  if (out.size() < width) out.append(width - out.size(), ' ');
  return out;
}

/// printf("%*s", width, text): spaces up to `width` bytes, then `text`.
inline std::string right_aligned(std::string_view text, std::size_t width) {
  std::string out;
  if (text.size() < width) out.append(width - text.size(), ' ');
  out += text;
  return out;
}

}  // namespace p3at
