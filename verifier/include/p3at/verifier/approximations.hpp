#pragma once
/// Where a mission is outside what the verifier's model vouches for: each
/// approximation the model makes on this mission (approximation_table.hpp
/// lists the kinds and their measured errors), found from the mission, the
/// models and the evaluation's own notes (outcome.hpp), and located in the
/// mission file. `verify()` fills VerifyResult::approximations with these;
/// the gate refuses a mission that is not evaluable (docs/verifier.md).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/approximation_table.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier {

/// The mission-file element an approximation is about.
enum class MissionElement { robot, max_speed, state, transition };

struct Approximation {
  ApproximationKind kind = ApproximationKind::noise_redrawn_in_leg;
  std::size_t robot = 0;                  ///< index into Mission::robots
  std::string robot_name;
  std::string state;                      ///< the state's name ("" when about the robot as a whole)
  MissionElement element = MissionElement::robot;
  std::size_t index = 0;                  ///< the state's or the transition's index (element state/transition)
  std::string where;                      ///< "file:line:col" of the element; empty until located
  std::string detail;                     ///< what was found, in words
  std::optional<MeasuredError> measured_error;  ///< the kind's row
  bool vouched = false;                   ///< the kind's row
};

/// The approximations of `mission` under `models`, given the evaluation's
/// outcome (races, concurrent legs, the pose error at each leg's entry),
/// sorted by robot, then kind. Not located
/// (`where` empty): locate_approximations() does that from the file's text.
std::vector<Approximation> detect_approximations(const mission::Mission& mission, const Models& models,
                                                 const SystemOutcome& outcome);

/// The approximations the mission file and the models show by themselves:
/// every kind but robots-racing and teammates-moving-near-path, which only the
/// evaluation finds (who races whom, which legs are driven at once). Each one
/// is also in detect_approximations()' answer for any outcome, so a mission
/// with an unvouched one here is not evaluable whatever the evaluation says:
/// the launch gate refuses it in milliseconds instead of evaluating it first
/// (a looped multi-robot mission can take minutes; docs/verifier.md, "Cost").
std::vector<Approximation> detect_approximations_before_evaluation(const mission::Mission& mission,
                                                                   const Models& models);

/// True when every approximation is vouched for: the verifier's answer is
/// within its validated bounds.
bool all_vouched(const std::vector<Approximation>& approximations);

/// The unvouched kinds' names, comma-separated, each once ("" if none).
std::string unvouched_kinds(const std::vector<Approximation>& approximations);

/// Finds mission elements in the mission file's text (the same bytes the
/// mission was parsed from; robots, states and transitions in file order, as
/// the loader keeps them): "file:line:column". Never throws; an element it
/// cannot find is "file".
class MissionLocator {
 public:
  MissionLocator(std::string_view mission_yaml, std::string mission_file);
  std::string where(std::size_t robot, MissionElement element, std::size_t index = 0) const;

 private:
  std::string file_;
  std::vector<std::string> robots_, speeds_;
  std::vector<std::vector<std::string>> states_, transitions_;
};

/// Fills each approximation's `where` with the locator.
void locate_approximations(std::vector<Approximation>& approximations, const MissionLocator& locator);

const char* to_string(ApproximationKind kind);  ///< the table's name, e.g. "fsa-loop"

}  // namespace p3at::verifier
