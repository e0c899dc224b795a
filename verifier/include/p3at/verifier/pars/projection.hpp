#pragma once
/// Hiding and projection (the seed paper's Defs. 5 and 6, and the simplified
/// projection (Sys')^n ↓ S of section V).

#include <functional>
#include <optional>
#include <set>
#include <string>

#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars {

/// Which processes a projection keeps.
using ProcessFilter = std::function<bool(const Term& process)>;

/// Def. 5, P abs S: every process that `keep` rejects becomes the internal action i.
Term hide(const Term& term, const ProcessFilter& keep);
/// Def. 5 with S given by process names.
Term hide(const Term& term, const std::set<std::string>& names);
/// Def. 6: adjacent internal actions in a composition are grouped into one
/// (i ; i = i, i | i = i, i # i = i), bottom-up; a composition of internal
/// actions only becomes i.
Term group_internal(const Term& term);
/// The projection onto S: hide, group, then drop the internal actions
/// altogether (P ; i = P, and so on); nullopt when nothing of S remains.
std::optional<Term> project(const Term& term, const ProcessFilter& keep);
std::optional<Term> project(const Term& term, const std::set<std::string>& names);
/// The names of the processes in a term (the S of "P abs Q").
std::set<std::string> process_names(const Term& term);

}  // namespace p3at::verifier::pars
