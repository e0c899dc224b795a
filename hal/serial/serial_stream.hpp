#pragma once
// Private to p3at_hal: a ByteStream over a serial port through libserialport.
// Users reach it through open_byte_stream("serial:///dev/ttyS0?baud=9600").

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "p3at/common/result.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/url.hpp"

struct sp_port;  // libserialport's handle; its header stays inside serial_stream.cpp

namespace p3at::hal {

/// Owns one open serial port, configured 8N1 without flow control.
class SerialStream final : public ByteStream {
 public:
  /// Baud rates a Pioneer controller can be set to (ARCOS default 9600).
  static constexpr int kBaudRates[] = {9600, 19200, 38400, 57600, 115200};

  /// Opens `url.path` (e.g. /dev/ttyUSB0) at `?baud=` (default 9600). `text`
  /// is the URL as written, used in every message. Errors:
  /// invalid_argument (bad URL form, baud or parameter), not_found (no such
  /// device, or not a serial port libserialport knows), refused (busy or
  /// permission denied), io (anything else the OS reports).
  static Result<std::unique_ptr<SerialStream>> open(const Url& url, const std::string& text);

  ~SerialStream() override;

  /// Waits at most 1000 ms plus the line time of `bytes` at this baud rate.
  Status write_all(std::span<const std::uint8_t> bytes) override;
  Result<std::size_t> read_some(std::span<std::uint8_t> buffer, int timeout_ms) override;
  void close() override;
  std::string describe() const override { return description_; }

 private:
  SerialStream(sp_port* port, int baud, std::string description)
      : port_(port), baud_(baud), description_(std::move(description)) {}
  Error closed_error() const;

  sp_port* port_ = nullptr;  // owned: sp_close + sp_free_port in close()
  int baud_ = 9600;
  std::string description_;
};

}  // namespace p3at::hal
