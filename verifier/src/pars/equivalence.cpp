#include "p3at/verifier/pars/equivalence.hpp"

#include "p3at/verifier/pars/printer.hpp"

namespace p3at::verifier::pars {

namespace {

std::string shape(const Term& t) {
  if (t.is_process()) return "the process " + t.name;
  return std::string("a '") + to_string(t.op) + "' composition of " + std::to_string(t.parts.size()) + " parts";
}

std::string plural(std::size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

bool match(const Term& p, const Term& q, StructuralMatch& result) {
  const auto differ = [&](const std::string& how) {
    result.mismatch = "'" + to_string(p) + "' and '" + to_string(q) + "' differ: " + how;
    return false;
  };
  if (p.is_process() != q.is_process()) return differ(shape(p) + " vs " + shape(q));
  if (p.is_process()) {
    if (p.name != q.name) return differ("process " + p.name + " vs process " + q.name);
    if (p.params.size() != q.params.size()) {
      return differ(p.name + " with " + plural(p.params.size(), "parameter") + " vs " +
                    plural(q.params.size(), "parameter"));
    }
    for (std::size_t i = 0; i < p.params.size(); ++i) {
      result.bindings.push_back(ParameterBinding{p.name, i, p.params[i], q.params[i]});
    }
    return true;
  }
  if (p.op != q.op || p.parts.size() != q.parts.size()) return differ(shape(p) + " vs " + shape(q));
  for (std::size_t i = 0; i < p.parts.size(); ++i) {
    if (!match(p.parts[i], q.parts[i], result)) return false;
  }
  return true;
}

}  // namespace

StructuralMatch structurally_equivalent(const Term& p, const Term& q) {
  StructuralMatch result;
  result.equivalent = match(flatten(p), flatten(q), result);
  if (!result.equivalent) result.bindings.clear();
  return result;
}

}  // namespace p3at::verifier::pars
