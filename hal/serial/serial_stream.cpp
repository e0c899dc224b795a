#include "serial/serial_stream.hpp"

#include <libserialport.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cstdint>
#include <system_error>

namespace p3at::hal {
namespace {

constexpr int kDefaultBaud = 9600;
constexpr std::int64_t kWriteMarginMs = 1000;
constexpr int kBitsPerByte8N1 = 10;  // start + 8 data + stop

Error::Code code_for_errno(int err) {
  switch (err) {
    case ENOENT:
    case ENODEV:
    case ENXIO: return Error::Code::not_found;
    case EBUSY:
    case EACCES:
    case EPERM: return Error::Code::refused;
    default: return Error::Code::io;
  }
}

// What a failed libserialport call left behind. Captured right after the
// call, before anything else can overwrite errno (SP_ERR_FAIL's details live there).
struct SpFailure {
  sp_return rc = SP_OK;
  int os_error = 0;
  std::string os_text;
};

SpFailure capture(sp_return rc) {
  SpFailure f;
  f.rc = rc;
  if (rc == SP_ERR_FAIL) {
    f.os_error = sp_last_error_code();
    if (char* msg = sp_last_error_message(); msg != nullptr) {
      f.os_text = msg;
      sp_free_error_message(msg);
    }
  }
  return f;
}

Error to_error(const std::string& what, const SpFailure& f) {
  switch (f.rc) {
    case SP_ERR_FAIL: {
      std::string hint;
      if (f.os_error == EACCES || f.os_error == EPERM) hint = " (is this user in the 'dialout' group?)";
      if (f.os_error == EBUSY) hint = " (another program has the port open)";
      const std::string os_text = f.os_text.empty() ? "error " + std::to_string(f.os_error) : f.os_text;
      return make_error(code_for_errno(f.os_error), what + ": " + os_text + hint);
    }
    case SP_ERR_ARG: return make_error(Error::Code::invalid_argument, what + ": libserialport rejected the arguments");
    case SP_ERR_MEM: return make_error(Error::Code::io, what + ": libserialport ran out of memory");
    case SP_ERR_SUPP: return make_error(Error::Code::io, what + ": not supported by this device or driver");
    case SP_OK: break;
  }
  return make_error(Error::Code::io, what + ": libserialport returned " + std::to_string(static_cast<int>(f.rc)));
}

// A serial adapter that disappears (USB unplugged) reports EIO/ENXIO/ENODEV:
// for the session that is the peer going away.
Error transfer_error(const std::string& what, const SpFailure& f) {
  Error e = to_error(what, f);
  if (f.rc == SP_ERR_FAIL && (f.os_error == EIO || f.os_error == ENXIO || f.os_error == ENODEV)) {
    e.code = Error::Code::closed;
  }
  return e;
}

std::string supported_bauds() {
  std::string out;
  for (const int b : SerialStream::kBaudRates) {
    if (!out.empty()) out += ", ";
    out += std::to_string(b);
  }
  return out;
}

Result<int> parse_baud(const Url& url, const std::string& text) {
  const std::string baud_text = url.query_or("baud", std::to_string(kDefaultBaud));
  int baud = 0;
  const auto [end, ec] = std::from_chars(baud_text.data(), baud_text.data() + baud_text.size(), baud);
  const bool is_number = !baud_text.empty() && ec == std::errc{} && end == baud_text.data() + baud_text.size();
  const auto& rates = SerialStream::kBaudRates;
  if (!is_number || std::find(std::begin(rates), std::end(rates), baud) == std::end(rates)) {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': baud '" + baud_text + "' is not supported (expected one of " + supported_bauds() + ")");
  }
  return baud;
}

Status check_url_form(const Url& url, const std::string& text) {
  if (!url.host.empty()) {
    return make_error(Error::Code::invalid_argument,
                      "'" + text + "': expected serial:///dev/NAME (three slashes; the device path follows 'serial://')");
  }
  if (url.path.empty() || url.path == "/") {
    return make_error(Error::Code::invalid_argument, "'" + text + "': expected a device path, as in serial:///dev/ttyS0");
  }
  for (const auto& [key, value] : url.query) {
    if (key != "baud") {
      return make_error(Error::Code::invalid_argument, "'" + text + "': unknown parameter '" + key + "' (expected baud)");
    }
  }
  return {};
}

}  // namespace

Result<std::unique_ptr<SerialStream>> SerialStream::open(const Url& url, const std::string& text) {
  if (auto st = check_url_form(url, text); !st) return st.error();
  auto baud = parse_baud(url, text);
  if (!baud) return baud.error();
  const std::string& device = url.path;

  // libserialport reports a missing device as a bare "invalid argument";
  // ask the file system first so the message can say what is wrong.
  struct stat info {};
  if (::stat(device.c_str(), &info) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      return make_error(Error::Code::not_found, "'" + text + "': no such device " + device);
    }
    return make_error(code_for_errno(err),
                      "'" + text + "': cannot access " + device + ": " + std::system_category().message(err));
  }

  sp_port* port = nullptr;
  const sp_return found = sp_get_port_by_name(device.c_str(), &port);
  if (found != SP_OK) {
    if (found == SP_ERR_FAIL) {
      const SpFailure f = capture(found);
      return to_error("'" + text + "': cannot look up " + device, f);
    }
    return make_error(Error::Code::not_found,
                      "'" + text + "': " + device +
                          " is not a serial port libserialport can use (it needs an entry under /sys/class/tty; "
                          "pseudo-terminals are not supported)");
  }
  if (const sp_return rc = sp_open(port, SP_MODE_READ_WRITE); rc != SP_OK) {
    const SpFailure f = capture(rc);
    Error e = to_error("'" + text + "': cannot open " + device, f);
    sp_free_port(port);
    return e;
  }
  // Takes ownership now: the destructor closes and frees the port.
  std::unique_ptr<SerialStream> stream(new SerialStream(port, *baud, text));

  const std::string what = "'" + text + "': cannot configure " + device;
  sp_return rc = sp_set_baudrate(port, *baud);
  if (rc == SP_OK) rc = sp_set_bits(port, 8);
  if (rc == SP_OK) rc = sp_set_parity(port, SP_PARITY_NONE);
  if (rc == SP_OK) rc = sp_set_stopbits(port, 1);
  if (rc == SP_OK) rc = sp_set_flowcontrol(port, SP_FLOWCONTROL_NONE);
  // Bytes queued before we opened belong to nobody's session.
  if (rc == SP_OK) rc = sp_flush(port, SP_BUF_BOTH);
  if (rc != SP_OK) return to_error(what, capture(rc));
  return stream;
}

SerialStream::~SerialStream() { close(); }

Error SerialStream::closed_error() const {
  return make_error(Error::Code::closed, description_ + ": stream is closed");
}

Status SerialStream::write_all(std::span<const std::uint8_t> bytes) {
  if (port_ == nullptr) return closed_error();
  if (bytes.empty()) return {};
  // The line itself needs bytes * 10 bits / baud; allow a fixed margin on top.
  const std::int64_t line_ms =
      static_cast<std::int64_t>(bytes.size()) * kBitsPerByte8N1 * 1000 / static_cast<std::int64_t>(baud_);
  const auto timeout_ms = static_cast<unsigned int>(std::min<std::int64_t>(line_ms + kWriteMarginMs, INT_MAX));
  const int n = sp_blocking_write(port_, bytes.data(), bytes.size(), timeout_ms);
  if (n < 0) {
    const SpFailure f = capture(static_cast<sp_return>(n));
    return transfer_error(description_ + ": write failed", f);
  }
  if (static_cast<std::size_t>(n) < bytes.size()) {
    return make_error(Error::Code::timeout, description_ + ": wrote only " + std::to_string(n) + " of " +
                                                std::to_string(bytes.size()) + " bytes within " +
                                                std::to_string(timeout_ms) + " ms");
  }
  return {};
}

Result<std::size_t> SerialStream::read_some(std::span<std::uint8_t> buffer, int timeout_ms) {
  if (port_ == nullptr) return closed_error();
  if (buffer.empty()) return std::size_t{0};
  // libserialport reads "0 ms" as "wait forever", so a poll must not block.
  const int n = timeout_ms <= 0
                    ? sp_nonblocking_read(port_, buffer.data(), buffer.size())
                    : sp_blocking_read_next(port_, buffer.data(), buffer.size(), static_cast<unsigned int>(timeout_ms));
  if (n < 0) {
    const SpFailure f = capture(static_cast<sp_return>(n));
    return transfer_error(description_ + ": read failed", f);
  }
  return static_cast<std::size_t>(n);
}

void SerialStream::close() {
  if (port_ != nullptr) {
    sp_close(port_);
    sp_free_port(port_);
    port_ = nullptr;
  }
}

}  // namespace p3at::hal
