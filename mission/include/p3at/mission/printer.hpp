#pragma once
/// The canonical YAML form of a mission: every field and every resolved
/// default written out, in schema order, so parse_mission(to_yaml(m)) == m.

#include <string>

#include "p3at/mission/mission.hpp"

namespace p3at::mission {

/// Writes `mission` as a mission file (docs/mission-format.md). Numbers are
/// printed in their shortest exact form, so they read back bit for bit.
std::string to_yaml(const Mission& mission);

}  // namespace p3at::mission
