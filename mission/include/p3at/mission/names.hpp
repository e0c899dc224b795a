#pragma once
/// A name as the mission format has it (robots, states, messages): 1 to 64
/// letters, digits or '_', not starting with a digit. The robot-models file
/// and calibration logs name robots the same way, so they check with this too.

#include <string_view>

namespace p3at::mission {

bool is_valid_name(std::string_view text);

}  // namespace p3at::mission
