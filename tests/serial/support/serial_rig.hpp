#pragma once
// What the serial rig's tests share (scripts/run-serial-tests.sh, docs/hal.md
// "Serial rig"): the tty under test, the guest port its far end reaches, the
// speed the kernel driver is set to, and an in-process far end for tests that
// need to shape the bytes themselves (p3at_sim on the port: rig_sim.hpp).

#include <fcntl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "child_process.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/tcp_listener.hpp"

namespace p3at::test::serial_rig {

/// The tty under test: $P3AT_SERIAL_DEVICE, default /dev/ttyS0.
inline std::string device() {
  const char* env = std::getenv("P3AT_SERIAL_DEVICE");
  return env != nullptr && *env != '\0' ? env : "/dev/ttyS0";
}

/// The TCP port (in this machine) that the tty's far end connects to:
/// $P3AT_SERIAL_PEER_PORT, set by the rig; 0 when unset.
inline int peer_port() {
  const char* env = std::getenv("P3AT_SERIAL_PEER_PORT");
  return env != nullptr ? std::atoi(env) : 0;
}

/// Empty when this process runs inside the rig (the tty exists, is a serial
/// port with a /sys/class/tty entry, and the far end's port is known); else why not.
inline std::string why_rig_unavailable() {
  if (peer_port() <= 0) {
    return "P3AT_SERIAL_PEER_PORT is not set: these tests run inside the serial rig, "
           "scripts/run-serial-tests.sh BUILD_DIR (docs/hal.md)";
  }
  const std::string dev = device();
  struct stat info {};
  if (::stat(dev.c_str(), &info) != 0 || !S_ISCHR(info.st_mode)) return "no character device " + dev;
  const std::string sys = "/sys/class/tty/" + dev.substr(dev.find_last_of('/') + 1);
  if (::stat(sys.c_str(), &info) != 0) return dev + " has no " + sys + " (not a serial port libserialport can use)";
  return {};
}

inline std::string url(int baud) { return "serial://" + device() + "?baud=" + std::to_string(baud); }

inline std::int64_t steady_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// The line speed the kernel's tty driver is set to now, read through a second
/// descriptor (termios belong to the tty, not to the descriptor); -1 on error.
inline int driver_baud() {
  const int fd = ::open(device().c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return -1;
  termios t{};
  const int rc = ::tcgetattr(fd, &t);
  ::close(fd);
  if (rc != 0) return -1;
  switch (::cfgetospeed(&t)) {
    case B9600: return 9600;
    case B19200: return 19200;
    case B38400: return 38400;
    case B57600: return 57600;
    case B115200: return 115200;
    default: return 0;
  }
}

/// Lets QEMU see that the line's previous far end has gone, so it reconnects
/// (about a second later) to whatever listens now. QEMU reads the TCP side
/// only while the UART can take bytes; with the tty closed, a few stale bytes
/// fill it, and the far end's close goes unnoticed until the tty is opened
/// and read. So: open, drain for a moment, close.
inline void kick_line() {
  auto opened = hal::open_byte_stream(url(9600));
  if (!opened.ok()) return;
  std::vector<std::uint8_t> buffer(256);
  const std::int64_t until = steady_ms() + 200;
  while (steady_ms() < until) {
    auto got = opened.value()->read_some(buffer, 50);
    if (!got.ok()) break;
  }
  opened.value()->close();
}

/// Waits until `connected()` holds, kicking the line while it does not.
template <class Predicate>
bool wait_for_line(Predicate connected, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (connected()) return true;
    kick_line();
    for (int i = 0; i < 30 && !connected(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return connected();
}

/// An in-process far end: listens on the peer port, accepts the line (QEMU's
/// connection) and runs `serve` on it in a thread until it returns or stop().
class FarEnd {
 public:
  using Serve = std::function<void(hal::ByteStream& line, const std::atomic<bool>& stop)>;

  explicit FarEnd(Serve serve) : serve_(std::move(serve)) {
    auto listener = hal::TcpListener::listen("", peer_port());
    if (!listener.ok()) {
      listen_error_ = listener.error().message;
      finished_ = true;
      return;
    }
    listener_ = std::move(listener).value();
    thread_ = std::thread([this] { run(); });
  }
  FarEnd(const FarEnd&) = delete;
  FarEnd& operator=(const FarEnd&) = delete;
  ~FarEnd() { stop(); }

  /// True once the line is connected (QEMU retries about once a second);
  /// false at once when the port could not be listened on (see listen_error()).
  bool wait_connected(double timeout_s = 10.0) const {
    if (!listen_error_.empty()) return false;
    return wait_for_line([this] { return connected_.load(); }, timeout_s);
  }
  bool finished() const { return finished_; }
  const std::string& listen_error() const { return listen_error_; }

  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run() {
    while (!stop_) {
      auto accepted = listener_->accept(50);
      if (!accepted.ok() || !*accepted) continue;
      std::unique_ptr<hal::ByteStream> line = std::move(accepted).value();
      connected_ = true;
      serve_(*line, stop_);
      line->close();
      break;
    }
    // Nothing listens any more: QEMU's reconnects are refused, the line stays dead.
    listener_.reset();
    finished_ = true;
  }

  Serve serve_;
  std::string listen_error_;
  std::unique_ptr<hal::TcpListener> listener_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  std::atomic<bool> finished_{false};
};

}  // namespace p3at::test::serial_rig
