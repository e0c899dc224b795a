#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/pars/printer.hpp"

namespace p3at::verifier {

namespace {

std::string comparison_text(const Comparison& c) {
  std::string out;
  for (std::size_t i = 0; i < c.left.size(); ++i) {
    if (i > 0) out += ", ";
    out += pars::to_string(c.left[i]);
  }
  out += " ";
  out += pars::to_string(c.op);
  out += " ";
  out += pars::to_string(c.right);
  return out;
}

}  // namespace

std::string to_string(const Constraint& k) {
  std::string out;
  if (k.probabilistic) out += "P(";
  for (std::size_t i = 0; i < k.events.size(); ++i) {
    if (i > 0) out += " and ";
    out += comparison_text(k.events[i]);
  }
  if (k.probabilistic) {
    out += ") ";
    out += pars::to_string(k.bound_op);
    out += " ";
    out += pars::format_number(k.bound);
  }
  return out;
}

std::string to_string(const Criterion& c) {
  std::string out = "criterion " + c.name + "\n";
  // A long network continues on indented lines, each ending with its operator.
  out += "network " + pars::to_pretty_string(c.network, 8) + "\n";
  if (!c.constraints.empty()) {
    out += "constraints\n";
    for (const Constraint& k : c.constraints) out += "  " + to_string(k) + "\n";
  }
  return out;
}

}  // namespace p3at::verifier
