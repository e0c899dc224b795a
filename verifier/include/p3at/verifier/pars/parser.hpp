#pragma once
/// Reading PARS text (grammar in docs/pars.md). Bad text throws ParseError
/// naming the first offending token as source:line:column and what was expected.

#include <stdexcept>
#include <string>
#include <string_view>

#include "p3at/common/located_error.hpp"
#include "p3at/verifier/pars/expr.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars {

/// Text that is not valid PARS. what() is "source:line:column: detail".
class ParseError : public LocatedError {
 public:
  using LocatedError::LocatedError;
  /// The source name (a file, or e.g. "<criterion>"): file().
  const std::string& source() const { return file(); }
};

/// Limits that keep hostile input from exhausting the stack.
inline constexpr int kMaxNesting = 200;   ///< parentheses, and depth of an expression tree

/// One term, e.g. "Delay<t1> ; (Delay<t2> # At<robot1, p>)".
Term parse_term(std::string_view text, const std::string& source_name = "<term>");
/// One expression without comparisons, e.g. "r + u * z(u, t) * t".
Expr parse_expr(std::string_view text, const std::string& source_name = "<expr>");
/// One expression, optionally compared: "|p - (1, 2)| <= 0.5".
Expr parse_condition(std::string_view text, const std::string& source_name = "<condition>");
/// A whole program: definitions, each optionally preceded by '#' comment lines.
Program parse_program(std::string_view text, const std::string& source_name = "<program>");

}  // namespace p3at::verifier::pars
