#include <string>

#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/url.hpp"
#include "serial/serial_stream.hpp"
#include "tcp/tcp_stream.hpp"

namespace p3at::hal {
namespace {

constexpr int kMaxPort = 65535;

Result<std::unique_ptr<ByteStream>> open_tcp(const Url& url, const std::string& text, int connect_timeout_ms) {
  if (url.host.empty()) {
    return make_error(Error::Code::invalid_argument, "'" + text + "': expected a host, as in tcp://127.0.0.1:8101");
  }
  if (url.port < 0) {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': missing port (expected tcp://" + url.host + ":PORT, e.g. port 8101)");
  }
  if (url.port == 0 || url.port > kMaxPort) {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': cannot connect to port " + std::to_string(url.port) + " (expected 1-65535)");
  }
  if (!url.path.empty() && url.path != "/") {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': unexpected path '" + url.path + "' (expected tcp://HOST:PORT)");
  }
  if (!url.query.empty()) {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': unknown parameter '" + url.query.begin()->first + "' (tcp:// takes none)");
  }
  auto stream = TcpStream::connect(text, url.host, url.port, connect_timeout_ms);
  if (!stream) return stream.error();
  return std::unique_ptr<ByteStream>(std::move(stream).value());
}

}  // namespace

Result<std::unique_ptr<ByteStream>> open_byte_stream(std::string_view url_text, int connect_timeout_ms) {
  const std::string text(url_text);
  if (connect_timeout_ms <= 0) {
    return make_error(Error::Code::invalid_argument, "'" + text + "': connect timeout must be > 0 ms, got " +
                                                         std::to_string(connect_timeout_ms));
  }
  auto url = parse_url(url_text);
  if (!url) return url.error();
  if (url->scheme == "tcp") return open_tcp(*url, text, connect_timeout_ms);
  if (url->scheme == "serial") {
    auto stream = SerialStream::open(*url, text);
    if (!stream) return stream.error();
    return std::unique_ptr<ByteStream>(std::move(stream).value());
  }
  return make_error(Error::Code::invalid_argument,
                    "unknown scheme '" + url->scheme + "' in '" + text + "' (expected tcp:// or serial://)");
}

}  // namespace p3at::hal
