#pragma once
// The commands a report names ("the commands that made it"): a document's
// own `command` key when it has one, else the command rebuilt from what the
// document records (its criterion point, its grid's axes as A:B:STEP, the
// validation's seed, runs, world and mission file).

#include <optional>
#include <string>
#include <vector>

#include "p3at/report/report_data.hpp"

namespace p3at::vipars::report {

/// A word as POSIX sh reads it back: unchanged when it is only safe
/// characters, else in single quotes.
std::string shell_quote(const std::string& word);
/// Words joined by spaces, each quoted as needed.
std::string shell_join(const std::vector<std::string>& words);

/// An evenly spaced axis as A:B:STEP (the --tmax-range/--rmax-range syntax),
/// or nothing when the spacing is uneven.
std::optional<std::string> range_text(const std::vector<double>& axis);

/// `vipars verify ... --json > OUTPUT`, from the verification document and
/// the mission and models files when known (placeholders otherwise).
std::string verify_command(const Side& verification, const std::string& mission_file, const std::string& models_file,
                           const std::string& output);
/// `vipars validate ... --json > OUTPUT`, from the validation document.
std::string validate_command(const Side& validation, const std::string& output);

}  // namespace p3at::vipars::report
