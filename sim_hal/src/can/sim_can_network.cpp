#include "p3at/sim/can/sim_can_network.hpp"

#include <algorithm>
#include <deque>
#include <vector>

namespace p3at::sim {
namespace {

class Endpoint;

}  // namespace

struct SimCanNetwork::Core {
  const hal::Clock& clock;
  std::size_t rx_queue_limit;
  hal::CanBusState state = hal::CanBusState::error_active;
  std::vector<Endpoint*> endpoints;
  std::uint64_t deliveries = 0;
};

namespace {

bool passes(const std::vector<hal::CanFilter>& filters, const can::Frame& frame) {
  if (filters.empty()) return true;
  return std::any_of(filters.begin(), filters.end(), [&](const hal::CanFilter& f) {
    return f.extended == frame.extended && (frame.id & f.mask) == (f.id & f.mask);
  });
}

class Endpoint final : public hal::CanBus {
 public:
  Endpoint(std::shared_ptr<SimCanNetwork::Core> core, std::string name)
      : core_(std::move(core)), name_("sim-can://" + std::move(name)) {
    status_.state = core_->state;
    core_->endpoints.push_back(this);
  }
  ~Endpoint() override {
    auto& list = core_->endpoints;
    list.erase(std::remove(list.begin(), list.end(), this), list.end());
  }

  Status send(const can::Frame& frame) override {
    if (!hal::can_communicate(core_->state)) {
      ++status_.send_failures;
      return make_error(Error::Code::state, name_ + ": bus is " + hal::to_string(core_->state) + ", frame " +
                                                can::format_frame(frame) + " not sent");
    }
    if (frame.length > can::kMaxDataLength) {
      ++status_.send_failures;
      return make_error(Error::Code::invalid_argument, name_ + ": frame length " + std::to_string(frame.length));
    }
    const std::int64_t now_us = core_->clock.now_us();
    for (Endpoint* other : core_->endpoints) {
      if (other != this) other->deliver(frame, now_us);
    }
    ++status_.frames_sent;
    return {};
  }

  Result<std::optional<hal::CanRxFrame>> receive() override {
    if (rx_.empty()) return std::optional<hal::CanRxFrame>{};
    hal::CanRxFrame rx = rx_.front();
    rx_.pop_front();
    ++status_.frames_received;
    return std::optional<hal::CanRxFrame>{rx};
  }

  Result<bool> wait(int /*timeout_ms*/) override { return !rx_.empty(); }

  Status set_filters(std::span<const hal::CanFilter> filters) override {
    filters_.assign(filters.begin(), filters.end());
    return {};
  }

  const hal::CanBusStatus& status() const override { return status_; }
  std::string describe() const override { return name_; }

  void deliver(const can::Frame& frame, std::int64_t now_us) {
    if (!passes(filters_, frame)) return;
    if (rx_.size() >= core_->rx_queue_limit) {
      ++status_.rx_dropped;
      return;
    }
    rx_.push_back(hal::CanRxFrame{frame, now_us});
    ++core_->deliveries;
  }

  void enter_state(hal::CanBusState next, const std::string& why) {
    const hal::CanBusState prev = status_.state;
    if (prev == next) return;
    if (next == hal::CanBusState::bus_off) ++status_.bus_off_events;
    if (next == hal::CanBusState::down) ++status_.down_events;
    if (!hal::can_communicate(prev) && hal::can_communicate(next)) ++status_.recoveries;
    status_.state = next;
    status_.last_error = name_ + ": " + hal::to_string(prev) + " -> " + hal::to_string(next) + " (" + why + ")";
  }

 private:
  std::shared_ptr<SimCanNetwork::Core> core_;
  std::string name_;
  std::deque<hal::CanRxFrame> rx_;
  std::vector<hal::CanFilter> filters_;
  hal::CanBusStatus status_;
};

}  // namespace

SimCanNetwork::SimCanNetwork(const hal::Clock& clock, std::size_t rx_queue_limit)
    : core_(std::make_shared<Core>(Core{clock, rx_queue_limit, hal::CanBusState::error_active, {}, 0})) {}

SimCanNetwork::~SimCanNetwork() = default;

std::unique_ptr<hal::CanBus> SimCanNetwork::attach(const std::string& name) {
  return std::make_unique<Endpoint>(core_, name);
}

void SimCanNetwork::set_state(hal::CanBusState state, const std::string& why) {
  core_->state = state;
  for (Endpoint* endpoint : core_->endpoints) endpoint->enter_state(state, why);
}

hal::CanBusState SimCanNetwork::state() const { return core_->state; }

std::uint64_t SimCanNetwork::deliveries() const { return core_->deliveries; }

}  // namespace p3at::sim
