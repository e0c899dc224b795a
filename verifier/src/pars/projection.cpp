#include "p3at/verifier/pars/projection.hpp"

#include <utility>

namespace p3at::verifier::pars {

Term hide(const Term& term, const ProcessFilter& keep) {
  if (term.is_process()) return keep(term) ? term : internal_action();
  Term out = term;
  for (Term& part : out.parts) part = hide(part, keep);
  return out;
}

Term hide(const Term& term, const std::set<std::string>& names) {
  return hide(term, [&names](const Term& p) { return names.count(p.name) > 0; });
}

Term group_internal(const Term& term) {
  if (term.is_process()) return term;
  std::vector<Term> parts;
  for (const Term& part : term.parts) {
    Term grouped = group_internal(part);
    if (is_internal_action(grouped) && !parts.empty() && is_internal_action(parts.back())) continue;
    parts.push_back(std::move(grouped));
  }
  return compose(term.op, std::move(parts));
}

namespace {
std::optional<Term> drop_internal(const Term& term) {
  if (term.is_process()) {
    if (is_internal_action(term)) return std::nullopt;
    return term;
  }
  std::vector<Term> parts;
  for (const Term& part : term.parts) {
    if (auto kept = drop_internal(part)) parts.push_back(std::move(*kept));
  }
  if (parts.empty()) return std::nullopt;
  return compose(term.op, std::move(parts));
}
}  // namespace

std::optional<Term> project(const Term& term, const ProcessFilter& keep) {
  return drop_internal(group_internal(hide(term, keep)));
}

std::optional<Term> project(const Term& term, const std::set<std::string>& names) {
  return drop_internal(group_internal(hide(term, names)));
}

std::set<std::string> process_names(const Term& term) {
  std::set<std::string> names;
  for_each_process(term, [&names](const Term& p) { names.insert(p.name); });
  return names;
}

}  // namespace p3at::verifier::pars
