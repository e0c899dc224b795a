#pragma once
// Shared helpers of the team-link tests: fixed keys and configs.

#include <cstdint>
#include <string>
#include <vector>

#include "p3at/team_link/team_key.hpp"
#include "p3at/team_link/team_protocol.hpp"

namespace p3at::test {

/// A key whose bytes are seed, seed+1, ... (distinct seeds → distinct keys).
inline hal::TeamKey fixed_key(std::uint8_t seed = 1) {
  hal::TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(seed + i);
  return hal::TeamKey(bytes);
}

inline hal::TeamLinkConfig team_config(const std::string& self,
                                       std::vector<std::string> roster = {"alpha", "bravo", "charlie"},
                                       const std::string& mission = "cbrn-search-1") {
  hal::TeamLinkConfig c;
  c.mission_id = mission;
  c.self = self;
  c.roster = std::move(roster);
  return c;
}

}  // namespace p3at::test
