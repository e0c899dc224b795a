#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <linux/can.h>

#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/url.hpp"
#include "socketcan/socketcan_bus.hpp"

namespace p3at::hal {
namespace {

Result<bool> parse_flag(const Url& url, std::string_view text, const std::string& key, bool fallback) {
  const std::string value = url.query_or(key, fallback ? "1" : "0");
  if (value == "1" || value == "true" || value == "on") return true;
  if (value == "0" || value == "false" || value == "off") return false;
  return make_error(Error::Code::invalid_argument,
                    "invalid URL '" + std::string(text) + "': " + key + "=" + value + " (expected 0 or 1)");
}

}  // namespace

Result<std::unique_ptr<CanBus>> open_can_bus(std::string_view text) {
  auto url = parse_url(text);
  if (!url) return url.error();
  if (url->scheme != "socketcan") {
    return make_error(Error::Code::invalid_argument, "unknown CAN bus scheme '" + url->scheme + "' in '" +
                                                         std::string(text) + "' (expected socketcan://IFNAME)");
  }
  if (url->port != -1 || (!url->path.empty() && url->path != "/")) {
    return make_error(Error::Code::invalid_argument,
                      "invalid URL '" + std::string(text) + "': expected socketcan://IFNAME, e.g. socketcan://can0");
  }
  for (const auto& [key, value] : url->query) {
    if (key != "loopback" && key != "receive_own") {
      return make_error(Error::Code::invalid_argument, "invalid URL '" + std::string(text) + "': unknown option '" +
                                                           key + "' (expected loopback or receive_own)");
    }
  }
  socketcan::SocketCanOptions options;
  options.url = std::string(text);
  options.interface_name = url->host;
  auto loopback = parse_flag(*url, text, "loopback", true);
  if (!loopback) return loopback.error();
  auto own = parse_flag(*url, text, "receive_own", false);
  if (!own) return own.error();
  options.loopback = *loopback;
  options.receive_own = *own;
  return socketcan::open_socketcan(options);
}

Status socketcan_available() {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int err = errno;
    return make_error(Error::Code::not_found, std::string("socket(AF_CAN, SOCK_RAW, CAN_RAW): ") + std::strerror(err));
  }
  ::close(fd);
  return {};
}

}  // namespace p3at::hal
