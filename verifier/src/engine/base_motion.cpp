#include "engine/base_motion.hpp"

#include <cmath>

namespace p3at::verifier::engine {

CycleIncrement step_cycle(BaseState& base, double command_trans_mps, double command_rot_radps,
                          const Kinematics& k) {
  return step_cycle_held(base, command_trans_mps, command_rot_radps, k, [](const BaseState&) { return false; });
}

bool at_rest(const BaseState& base) { return std::abs(base.trans_mps) < 1e-6 && std::abs(base.rot_radps) < 1e-6; }

}  // namespace p3at::verifier::engine
