#include "p3at/executive/behaviors.hpp"

#include <algorithm>

namespace p3at::exec {

Velocity<double> spin_command(const mission::SpinParams& params, const BehaviorConfig& config) {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  const double rate_radps = std::clamp(params.rate_deg_s * kDegToRad, -config.max_rot_radps, config.max_rot_radps);
  return Velocity<double>{0.0, rate_radps};
}

}  // namespace p3at::exec
