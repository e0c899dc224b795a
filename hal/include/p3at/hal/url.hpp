#pragma once
/// Device URLs such as `tcp://127.0.0.1:8101`, `serial:///dev/ttyS0?baud=9600`,
/// `socketcan://can0`, `sim://robot1`.

#include <map>
#include <string>
#include <string_view>

#include "p3at/common/result.hpp"

namespace p3at::hal {

struct Url {
  std::string scheme;                        ///< before "://", lower case
  std::string host;                          ///< authority without port (may be empty); IPv6 without brackets
  int port = -1;                             ///< 0-65535, or -1 when absent
  std::string path;                          ///< from the first '/' after the authority
  std::map<std::string, std::string> query;  ///< key=value pairs after '?', '&'-separated

  /// Value of a query parameter, or `fallback` when absent.
  std::string query_or(const std::string& key, const std::string& fallback) const;
};

/// Parses `scheme://authority/path?k=v&k2=v2`; the authority is `host`,
/// `host:port`, `[ipv6]` or `[ipv6]:port`. No percent-decoding. Errors are
/// Error::Code::invalid_argument naming the URL and what was expected.
Result<Url> parse_url(std::string_view text);

}  // namespace p3at::hal
