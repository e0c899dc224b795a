#pragma once
/// The abort condition Ω of a process (the seed paper's Def. 9):
///   Ω(P)     = cond(P)        if P is a condition process,
///   Ω(P | Q) = Ω(P) ∨ Ω(Q),   Ω(P # Q) = Ω(P) ∨ Ω(Q),
///   Ω(P ; Q) = Ω(P) ; Ω(Q)    (Ω(P) holds, and then, once P has ended, Ω(Q)).
/// Any other process never aborts by itself: Ω = never. That includes calls of
/// other definitions, which are other components with conditions of their own
/// (so a translated FSA state's Ω is exactly its triggers' conditions).
/// Simplifications: never ∨ X = X, and X ; never = X (if Q never aborts, P ; Q
/// aborts exactly when P does).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/verifier/pars/expr.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars {

struct Condition {
  enum class Kind { never, atom, any, then };
  Kind kind = Kind::never;
  Term process;               ///< atom: the condition process
  Expr expr;                  ///< atom: cond(process)
  std::vector<Condition> parts;   ///< any: the disjuncts; then: in order (>= 2 each)

  bool operator==(const Condition&) const = default;
};

/// True for the basic condition processes: the paper's EQ, NEQ, LT, GT, LEQ,
/// GEQ (two parameters compared) and the translator's triggers Is_at_goal,
/// Has_turned, Got_message and Message_sent (docs/pars.md lists their conditions).
bool is_condition_process(const Term& process);
/// cond(P) for a condition process: EQ<a, b> is a = b; Is_at_goal<g, r>(d) is
/// |d - g| <= r; Has_turned<a, o>(d) is turned(d) >= a - o; Got_message<m>(c)
/// is received(c); Message_sent<m>(c) is acked(c). nullopt when `process` is
/// not a condition process or has the wrong number of parameters or ports.
std::optional<Expr> condition_of(const Term& process);

/// Ω(term), simplified as above.
Condition abort_condition(const Term& term);
/// Ω of a definition: of its body, with the tail call of a TR definition (the
/// recursion, not a successor) never aborting.
Condition abort_condition(const Definition& definition);

/// "never", a condition's expression, "A or B", "A ; B" (';' binds tighter than "or").
std::string to_string(const Condition& condition);

}  // namespace p3at::verifier::pars
