#include "socketcan/socketcan_bus.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <utility>

#include "socketcan/error_frame.hpp"

namespace p3at::hal::socketcan {
namespace {

std::string errno_text(int err) { return std::strerror(err); }

bool would_block(int err) {
#if EAGAIN == EWOULDBLOCK
  return err == EAGAIN;
#else
  return err == EAGAIN || err == EWOULDBLOCK;
#endif
}

// Data frames this long after a bus-off, without a restart report, count as recovery.
constexpr std::int64_t kMissedRestartUs = 1'000'000;

// The interface is down (ENETDOWN) or gone (ENODEV, ENXIO: our binding died with it).
bool is_link_error(int err) { return err == ENETDOWN || err == ENODEV || err == ENXIO; }

std::int64_t steady_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::int64_t realtime_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// IFF_* flags of an interface, via a throwaway datagram socket (works whatever
// state our CAN socket is in). nullopt when the interface does not exist.
std::optional<unsigned> interface_flags(const std::string& name) {
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return std::nullopt;
  ifreq req{};
  std::strncpy(req.ifr_name, name.c_str(), IFNAMSIZ - 1);
  const int rc = ::ioctl(fd, SIOCGIFFLAGS, &req);
  ::close(fd);
  if (rc < 0) return std::nullopt;
  return static_cast<unsigned>(static_cast<unsigned short>(req.ifr_flags));
}

class SocketCanBus final : public CanBus {
 public:
  explicit SocketCanBus(SocketCanOptions options) : options_(std::move(options)) {}
  ~SocketCanBus() override { close_socket(); }

  Status open_socket();

  Status send(const can::Frame& frame) override;
  Result<std::optional<CanRxFrame>> receive() override;
  Result<bool> wait(int timeout_ms) override;
  Status set_filters(std::span<const CanFilter> filters) override;
  const CanBusStatus& status() const override { return status_; }
  std::string describe() const override { return options_.url; }

 private:
  void close_socket() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  Status apply_filters();
  void enter_state(CanBusState next, const std::string& why);
  void on_link_error(int err, const char* op);
  void try_recover();
  void on_error_frame(const can_frame& raw);
  Error fail(Error::Code code, const std::string& what) {
    status_.last_error = options_.url + ": " + what;
    return make_error(code, status_.last_error);
  }

  SocketCanOptions options_;
  int fd_ = -1;
  bool need_reopen_ = false;
  std::int64_t bus_off_since_us_ = 0;
  std::vector<CanFilter> filters_;
  CanBusStatus status_;
};

Status SocketCanBus::open_socket() {
  close_socket();
  const unsigned index = ::if_nametoindex(options_.interface_name.c_str());
  if (index == 0) {
    return fail(Error::Code::not_found, "no CAN interface '" + options_.interface_name + "' (" + errno_text(errno) + ")");
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    const int err = errno;
    return fail(err == EAFNOSUPPORT ? Error::Code::not_found : Error::Code::io,
                "socket(AF_CAN): " + errno_text(err));
  }
  fd_ = fd;
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  const int loopback = options_.loopback ? 1 : 0;
  const int recv_own = options_.receive_own ? 1 : 0;
  const int on = 1;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0 ||
      ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_LOOPBACK, &loopback, sizeof loopback) < 0 ||
      ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &recv_own, sizeof recv_own) < 0 ||
      ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof on) < 0 ||
      ::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) < 0) {
    const int err = errno;
    close_socket();
    return fail(Error::Code::io, "setsockopt: " + errno_text(err));
  }
  if (auto st = apply_filters(); !st) {
    close_socket();
    return st;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) {
    const int err = errno;
    close_socket();
    return fail(Error::Code::io, "bind to " + options_.interface_name + ": " + errno_text(err));
  }
  need_reopen_ = false;
  return {};
}

Status SocketCanBus::apply_filters() {
  if (fd_ < 0) return {};  // applied when the socket is (re)opened
  std::vector<can_filter> raw;
  if (filters_.empty()) {
    raw.push_back(can_filter{0, 0});  // everything
  } else {
    raw.reserve(filters_.size());
    for (const CanFilter& f : filters_) {
      const canid_t id_mask = f.extended ? CAN_EFF_MASK : CAN_SFF_MASK;
      // The EFF flag in the mask makes the format part of the match.
      raw.push_back(can_filter{(f.id & id_mask) | (f.extended ? CAN_EFF_FLAG : 0u), (f.mask & id_mask) | CAN_EFF_FLAG});
    }
  }
  const auto bytes = static_cast<socklen_t>(raw.size() * sizeof(can_filter));
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, raw.data(), bytes) < 0) {
    return fail(Error::Code::io, "setting " + std::to_string(raw.size()) + " receive filters: " + errno_text(errno));
  }
  return {};
}

Status SocketCanBus::set_filters(std::span<const CanFilter> filters) {
  filters_.assign(filters.begin(), filters.end());
  return apply_filters();
}

void SocketCanBus::enter_state(CanBusState next, const std::string& why) {
  const CanBusState prev = status_.state;
  if (next == prev) return;
  if (next == CanBusState::bus_off) {
    ++status_.bus_off_events;
    bus_off_since_us_ = steady_now_us();
  }
  if (next == CanBusState::down) ++status_.down_events;
  if (!can_communicate(prev) && can_communicate(next)) ++status_.recoveries;
  status_.state = next;
  status_.last_error = options_.url + ": " + to_string(prev) + " -> " + to_string(next) + " (" + why + ")";
}

void SocketCanBus::on_link_error(int err, const char* op) {
  // ENODEV/ENXIO: the interface was removed, and the kernel unbound our socket with it.
  if (err != ENETDOWN) need_reopen_ = true;
  enter_state(CanBusState::down, std::string(op) + ": " + errno_text(err));
}

void SocketCanBus::try_recover() {
  if (status_.state != CanBusState::down && !need_reopen_ && fd_ >= 0) return;
  const std::optional<unsigned> flags = interface_flags(options_.interface_name);
  if (!flags) {
    need_reopen_ = true;  // still gone
    return;
  }
  if ((*flags & IFF_UP) == 0) return;
  if (need_reopen_ || fd_ < 0) {
    if (!open_socket()) return;  // last_error says why; retried on the next call
    enter_state(CanBusState::error_active, "interface " + options_.interface_name + " is back, socket reopened");
    return;
  }
  enter_state(CanBusState::error_active, "interface " + options_.interface_name + " is up again");
}

void SocketCanBus::on_error_frame(const can_frame& raw) {
  ++status_.error_frames;
  std::array<std::uint8_t, 8> data{};
  std::copy(std::begin(raw.data), std::end(raw.data), data.begin());
  const ErrorFrameReport report = decode_error_frame(raw.can_id, data);
  if (report.overflow) ++status_.controller_overflows;
  if (report.has_counters) {
    status_.tx_error_counter = report.tx_error_counter;
    status_.rx_error_counter = report.rx_error_counter;
  }
  if (report.state) {
    enter_state(*report.state, "error frame: " + report.description);
  } else {
    status_.last_error = options_.url + ": error frame: " + report.description;
  }
}

Status SocketCanBus::send(const can::Frame& frame) {
  try_recover();
  if (!can_communicate(status_.state) || fd_ < 0) {
    ++status_.send_failures;
    return make_error(Error::Code::state,
                      options_.url + ": bus is " + to_string(status_.state) + ", frame " + can::format_frame(frame) +
                          " not sent");
  }
  can_frame raw{};
  raw.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  if (frame.remote) raw.can_id |= CAN_RTR_FLAG;
  raw.len = std::min<std::uint8_t>(frame.length, CAN_MAX_DLEN);
  std::copy_n(frame.data.begin(), raw.len, raw.data);
  for (;;) {
    const ssize_t n = ::write(fd_, &raw, sizeof raw);
    if (n == static_cast<ssize_t>(sizeof raw)) break;
    const int err = n < 0 ? errno : EIO;
    if (err == EINTR) continue;
    ++status_.send_failures;
    if (is_link_error(err)) {
      on_link_error(err, "send");
      return make_error(Error::Code::state, status_.last_error);
    }
    if (would_block(err) || err == ENOBUFS) {
      return fail(Error::Code::io, "transmit queue full, frame " + can::format_frame(frame) + " dropped");
    }
    return fail(Error::Code::io, "send " + can::format_frame(frame) + ": " + errno_text(err));
  }
  ++status_.frames_sent;
  return {};
}

Result<std::optional<CanRxFrame>> SocketCanBus::receive() {
  try_recover();
  if (fd_ < 0) return std::optional<CanRxFrame>{};
  for (;;) {
    can_frame raw{};
    iovec iov{&raw, sizeof raw};
    alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(timeval)) + CMSG_SPACE(sizeof(std::uint32_t))> control{};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control.data();
    msg.msg_controllen = control.size();
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      const int err = errno;
      if (err == EINTR) continue;
      if (would_block(err)) return std::optional<CanRxFrame>{};
      if (is_link_error(err)) {
        on_link_error(err, "receive");
        return std::optional<CanRxFrame>{};
      }
      return fail(Error::Code::io, "receive: " + errno_text(err));
    }
    if (n != static_cast<ssize_t>(sizeof raw)) continue;  // not a classic frame (we never enable CAN FD)

    std::int64_t stamp_us = steady_now_us();
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMP) {
        timeval tv{};
        std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
        std::int64_t kernel_real_us = tv.tv_sec;  // time_t and suseconds_t widen losslessly
        kernel_real_us = kernel_real_us * 1'000'000 + tv.tv_usec;
        // Map the kernel's wall-clock stamp onto the steady clock: how long ago it was, before now.
        stamp_us -= std::max<std::int64_t>(0, realtime_now_us() - kernel_real_us);
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t dropped = 0;
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        status_.rx_dropped = dropped;
      }
    }

    if ((raw.can_id & CAN_ERR_FLAG) != 0) {
      on_error_frame(raw);
      continue;
    }
    if (status_.state == CanBusState::down) {
      enter_state(CanBusState::error_active, "frames arriving again");
    } else if (status_.state == CanBusState::bus_off && stamp_us - bus_off_since_us_ > kMissedRestartUs) {
      // can-dev reports every restart (CAN_ERR_RESTARTED); frames in flight right after a bus-off are
      // no proof of recovery, but traffic long after it means we missed the report (e.g. an overflow).
      enter_state(CanBusState::error_active, "frames arriving long after bus-off, restart report missed");
    }
    CanRxFrame rx;
    rx.stamp_us = stamp_us;
    rx.frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    rx.frame.remote = (raw.can_id & CAN_RTR_FLAG) != 0;
    rx.frame.id = raw.can_id & (rx.frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    rx.frame.length = std::min<std::uint8_t>(raw.len, CAN_MAX_DLEN);
    std::copy_n(raw.data, rx.frame.length, rx.frame.data.begin());
    ++status_.frames_received;
    return std::optional<CanRxFrame>{rx};
  }
}

Result<bool> SocketCanBus::wait(int timeout_ms) {
  try_recover();
  if (fd_ < 0) {
    // Nothing to wait on while the interface is gone; pace the caller's retries.
    if (timeout_ms > 0) ::usleep(static_cast<useconds_t>(std::min(timeout_ms, 100)) * 1000u);
    return false;
  }
  pollfd pfd{fd_, POLLIN, 0};
  for (;;) {
    const int rc = ::poll(&pfd, 1, std::max(timeout_ms, 0));
    if (rc >= 0) return rc > 0;
    if (errno != EINTR) return fail(Error::Code::io, "poll: " + errno_text(errno));
  }
}

}  // namespace

Result<std::unique_ptr<CanBus>> open_socketcan(const SocketCanOptions& options) {
  if (options.interface_name.empty() || options.interface_name.size() >= IFNAMSIZ) {
    return make_error(Error::Code::invalid_argument,
                      "invalid URL '" + options.url + "': expected socketcan://IFNAME with a name of 1-" +
                          std::to_string(IFNAMSIZ - 1) + " characters");
  }
  auto bus = std::make_unique<SocketCanBus>(options);
  if (auto st = bus->open_socket(); !st) return st.error();
  return std::unique_ptr<CanBus>(std::move(bus));
}

}  // namespace p3at::hal::socketcan
