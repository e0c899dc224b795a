#pragma once
// How a VerifyResult is shown: JSON for machines (keys shared with
// `vipars validate`, docs/verifier.md) and readable text for people.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::vipars {

nlohmann::json verify_json(const mission::Mission& mission, const verifier::VerifyResult& result);
/// The probabilities, per-robot predictions, decision and (if any) the grid as a small table.
std::string verify_text(const mission::Mission& mission, const verifier::VerifyResult& result);
/// Fills the approximations' and blocked robots' file:line:column from the
/// mission file (read again; the text the mission was loaded from).
void locate_from_file(verifier::VerifyResult& result, const std::string& mission_file);
/// The `approximations` list of verify's JSON (docs/verifier.md).
nlohmann::json approximations_json(const std::vector<verifier::Approximation>& approximations);
/// The same for people: one entry per approximation (kind, robot, state, where, measured error, detail).
std::string approximations_text(const std::vector<verifier::Approximation>& approximations);

}  // namespace p3at::vipars
