#pragma once
/// PARS process terms (the seed paper, section IV.A; syntax in docs/pars.md).
///
/// A process is written Name<parameters>(in ports)(out ports) -> (results):
/// the paper's C_{u1,u2}(i1,i2)(o1,o2)^{v1,v2}; empty lists are left out, and
/// (in ports) alone means no out ports. Processes are composed with
/// ';' (sequential), '|' (parallel-max) and '#' (parallel-min / disabling).
/// Compositions are n-ary: `a ; b ; c` is one sequence of three parts, while
/// `(a ; b) ; c` is a sequence whose first part is itself a sequence; the
/// parser and the printer keep that distinction, so parse(print(t)) == t.
///
/// A program is a list of named definitions, Name<formals>(ins)(outs) = body.
/// A definition is tail-recursive (TR) when its body is `B ; Name<new>(...)`,
/// the paper's P_u = P'_u ; P_f(u).

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/verifier/pars/expr.hpp"

namespace p3at::verifier::pars {

/// The composition operators, loosest binding first: '#' < '|' < ';'.
enum class Op { disabling, parallel, sequence };
/// "#", "|", ";".
const char* to_string(Op op);

struct Term {
  enum class Kind { process, composition };
  Kind kind = Kind::process;

  // kind process: a basic process, or a call of a defined one (same syntax).
  std::string name;
  std::vector<Expr> params;
  std::vector<std::string> in_ports;
  std::vector<std::string> out_ports;
  std::vector<std::string> results;

  // kind composition: two or more parts joined by one operator.
  Op op = Op::sequence;
  std::vector<Term> parts;

  bool is_process() const { return kind == Kind::process; }
  bool operator==(const Term&) const = default;
};

/// The internal action `i` of Def. 5 (what hiding leaves of a process).
inline constexpr std::string_view kInternalAction = "i";

Term process(std::string name, std::vector<Expr> params = {}, std::vector<std::string> in_ports = {},
             std::vector<std::string> out_ports = {});
/// An n-ary composition; a single part is returned as it is (no composition of one).
Term compose(Op op, std::vector<Term> parts);
Term sequence(std::vector<Term> parts);
Term parallel(std::vector<Term> parts);
Term disabling(std::vector<Term> parts);
Term internal_action();
bool is_internal_action(const Term& term);

/// The same term with nested compositions of the same operator merged into
/// their parent: (a ; b) ; c becomes a ; b ; c (';', '|' and '#' are associative).
Term flatten(const Term& term);

/// Calls `visit` on every process of `term`, left to right.
void for_each_process(const Term& term, const std::function<void(const Term&)>& visit);

struct Definition {
  std::string name;
  std::vector<std::string> params;       ///< formal parameter names
  std::vector<std::string> in_ports;     ///< formal in ports
  std::vector<std::string> out_ports;    ///< formal out ports
  std::vector<std::string> results;      ///< result value names
  Term body;
  std::string comment;                   ///< printed as '#' lines before it (may contain '\n')

  bool operator==(const Definition&) const = default;
};

struct Program {
  std::vector<Definition> definitions;

  /// The definition with that name, or nullptr.
  const Definition* find(std::string_view name) const;
  bool operator==(const Program&) const = default;
};

/// The recursive call that ends a tail-recursive definition's body (the last
/// part of its top-level sequence, calling the definition itself), or nullptr
/// when the definition is not tail-recursive. The rest of the body (the period
/// process P') must not call the definition.
const Term* tail_call(const Definition& definition);
bool is_tail_recursive(const Definition& definition);

}  // namespace p3at::verifier::pars
