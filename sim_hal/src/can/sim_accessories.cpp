#include "p3at/sim/can/sim_accessories.hpp"

namespace p3at::sim {

SimAccessories::SimAccessories(hal::CanBus& bus, SimGyroConfig gyro, SimSafetyNodeConfig safety, bool with_gyro,
                               bool with_safety)
    : bus_(bus), gyro_(gyro), safety_(safety), with_gyro_(with_gyro), with_safety_(with_safety) {}

Status SimAccessories::step(std::int64_t now_us, double true_yaw_rate_radps) {
  for (int i = 0; i < 1000; ++i) {
    auto rx = bus_.receive();
    if (!rx) return rx.error();
    if (!rx->has_value()) break;
    ++frames_received_;
    const can::Frame& frame = (*rx)->frame;
    if (with_gyro_) gyro_.on_frame(frame);
    if (with_safety_) safety_.on_frame(frame);
  }
  Status first_error;
  if (with_gyro_) {
    if (auto st = gyro_.step(bus_, now_us, true_yaw_rate_radps); !st) first_error = st;
  }
  if (with_safety_) {
    if (auto st = safety_.step(bus_, now_us); !st && first_error) first_error = st;
  }
  return first_error;
}

}  // namespace p3at::sim
