#pragma once
/// Composition structural equivalence (the seed paper's Def. 7):
///   P ≡s Q  iff  P = Q, or P = P1 ⊕ P2 and Q = Q1 ⊕ Q2 with the same ⊕ in
///   {';', '|', '#'} and P1 ≡s Q1, P2 ≡s Q2.
/// Compared on flattened terms (n-ary compositions, part by part, in order).
/// Two processes match when they have the same name and the same number of
/// parameters; their parameters may differ, and each pair is returned as a
/// binding: the constraints C' that the match posts (t1 = (n-1)t, a = f^n(p)).
/// Ports are the system's wiring and are not compared.

#include <cstddef>
#include <string>
#include <vector>

#include "p3at/verifier/pars/expr.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars {

struct ParameterBinding {
  std::string process;   ///< the processes' name
  std::size_t index = 0; ///< which parameter
  Expr left;             ///< P's parameter
  Expr right;            ///< Q's parameter
  bool operator==(const ParameterBinding&) const = default;
};

struct StructuralMatch {
  bool equivalent = false;
  /// When not equivalent: where and how they differ, naming both sub-terms.
  std::string mismatch;
  /// When equivalent: every parameter pair, left to right.
  std::vector<ParameterBinding> bindings;
};

StructuralMatch structurally_equivalent(const Term& p, const Term& q);

}  // namespace p3at::verifier::pars
