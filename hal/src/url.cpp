#include "p3at/hal/url.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <system_error>

namespace p3at::hal {
namespace {

constexpr int kMaxPort = 65535;

Error bad_url(std::string_view text, const std::string& what) {
  return make_error(Error::Code::invalid_argument, "invalid URL '" + std::string(text) + "': " + what);
}

bool is_alpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool is_alnum(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }
bool is_hex(char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; }
char to_lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// RFC 3986: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." )
bool valid_scheme(std::string_view s) {
  if (s.empty() || !is_alpha(s.front())) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return is_alnum(c) || c == '+' || c == '-' || c == '.'; });
}

// Host names, IPv4 literals and interface names such as can0.
bool valid_reg_name(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return is_alnum(c) || c == '-' || c == '.' || c == '_'; });
}

bool valid_ipv6_literal(std::string_view s) {
  if (s.find(':') == std::string_view::npos) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return is_hex(c) || c == ':' || c == '.'; });
}

Result<int> parse_port(std::string_view text, std::string_view port_text) {
  if (port_text.empty()) return bad_url(text, "expected a port number after ':'");
  if (!std::all_of(port_text.begin(), port_text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return bad_url(text, "port '" + std::string(port_text) + "' is not a number (expected 0-65535)");
  }
  int port = 0;
  const auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc{} || end != port_text.data() + port_text.size() || port > kMaxPort) {
    return bad_url(text, "port " + std::string(port_text) + " is out of range (expected 0-65535)");
  }
  return port;
}

Status parse_authority(std::string_view text, std::string_view authority, Url& url) {
  if (authority.find('@') != std::string_view::npos) {
    return bad_url(text, "user information ('@') is not supported (expected host[:port])");
  }
  std::string_view host = authority;
  std::string_view port_text;
  bool has_port = false;
  if (!authority.empty() && authority.front() == '[') {
    const std::size_t close = authority.find(']');
    if (close == std::string_view::npos) return bad_url(text, "expected ']' to close the IPv6 address");
    host = authority.substr(1, close - 1);
    if (!valid_ipv6_literal(host)) {
      return bad_url(text, "'" + std::string(host) + "' is not an IPv6 address (expected [hex:hex:...])");
    }
    const std::string_view after = authority.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') return bad_url(text, "expected ':PORT' or nothing after ']'");
      port_text = after.substr(1);
      has_port = true;
    }
  } else {
    const std::size_t colon = authority.find(':');
    if (colon != std::string_view::npos) {
      if (authority.find(':', colon + 1) != std::string_view::npos) {
        return bad_url(text, "more than one ':' in the host (an IPv6 address must be in brackets: [::1]:PORT)");
      }
      host = authority.substr(0, colon);
      port_text = authority.substr(colon + 1);
      has_port = true;
    }
    if (!valid_reg_name(host)) {
      return bad_url(text, "host '" + std::string(host) + "' has characters other than letters, digits, '-', '.', '_'");
    }
    if (has_port && host.empty()) return bad_url(text, "expected a host before ':PORT'");
  }
  if (has_port) {
    auto port = parse_port(text, port_text);
    if (!port) return port.error();
    url.port = *port;
  }
  url.host = std::string(host);
  return {};
}

Status parse_query(std::string_view text, std::string_view query, Url& url) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    if (item.empty()) continue;  // tolerate "?a=1&&b=2" and a trailing '&'
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      return bad_url(text, "query item '" + std::string(item) + "' has no '=' (expected key=value)");
    }
    std::string key(item.substr(0, eq));
    if (key.empty()) return bad_url(text, "query item '" + std::string(item) + "' has an empty key (expected key=value)");
    if (url.query.count(key) != 0) return bad_url(text, "query key '" + key + "' appears twice");
    url.query.emplace(std::move(key), std::string(item.substr(eq + 1)));
  }
  return {};
}

}  // namespace

std::string Url::query_or(const std::string& key, const std::string& fallback) const {
  const auto it = query.find(key);
  return it == query.end() ? fallback : it->second;
}

Result<Url> parse_url(std::string_view text) {
  const bool has_control_or_space =
      std::any_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) <= ' ' || c == 0x7f; });
  if (has_control_or_space) return bad_url(text, "contains spaces or control characters");
  if (text.find('#') != std::string_view::npos) return bad_url(text, "fragments ('#') are not supported");

  const std::size_t sep = text.find("://");
  if (sep == std::string_view::npos) return bad_url(text, "expected scheme://authority/path, e.g. tcp://127.0.0.1:8101");
  const std::string_view scheme = text.substr(0, sep);
  if (!valid_scheme(scheme)) {
    return bad_url(text, "scheme '" + std::string(scheme) +
                             "' must start with a letter and hold only letters, digits, '+', '-', '.'");
  }

  Url url;
  url.scheme.resize(scheme.size());
  std::transform(scheme.begin(), scheme.end(), url.scheme.begin(), to_lower);

  std::string_view rest = text.substr(sep + 3);
  std::string_view query;
  if (const std::size_t q = rest.find('?'); q != std::string_view::npos) {
    query = rest.substr(q + 1);
    rest = rest.substr(0, q);
  }
  const std::size_t slash = rest.find('/');
  const std::string_view authority = rest.substr(0, slash);
  if (slash != std::string_view::npos) url.path = std::string(rest.substr(slash));

  if (auto st = parse_authority(text, authority, url); !st) return st.error();
  if (auto st = parse_query(text, query, url); !st) return st.error();
  return url;
}

}  // namespace p3at::hal
