#pragma once
// p3at_can_sim's stdin commands: parsed into an action on the simulated nodes.

#include <string>
#include <string_view>

#include "p3at/common/result.hpp"
#include "p3at/sim/can/sim_accessories.hpp"

namespace p3at::can_sim {

/// What a command line asks besides node changes.
struct CommandEffect {
  bool quit = false;
  bool has_rate = false;
  double rate_radps = 0.0;  ///< new true yaw rate when has_rate
};

/// The help text listing every command.
const char* command_help();

/// Applies one line ("estop on", "bumpers 0x11", "rate 0.5", …) to `nodes`.
/// Blank lines and '#' comments do nothing. Unknown or malformed commands are
/// an invalid_argument Error naming the line and what was expected.
Result<CommandEffect> apply_command(std::string_view line, sim::SimAccessories& nodes);

}  // namespace p3at::can_sim
