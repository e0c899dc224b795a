#pragma once
/// Writing PARS text. Every printer here writes what the parser reads back
/// equal: parse_term(to_string(t)) == t, parse_program(to_string(p)) == p.
/// Parentheses are minimal: only where precedence (';' binds tightest, then
/// '|', then '#') or a nested composition of the same operator needs them
/// (broken over lines, nested compositions are always parenthesised).

#include <cstddef>
#include <string>

#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars {

/// One line.
std::string to_string(const Term& term);
/// A process's header without composition: Name<params>(ins)(outs) -> (results).
std::string header_string(const Definition& definition);
/// One definition, broken over lines (operators at line ends, parts indented)
/// where the one-line form is wider than `width`; preceded by its comment.
std::string to_string(const Definition& definition, std::size_t width = 100);
/// Every definition, separated by blank lines.
std::string to_string(const Program& program, std::size_t width = 100);
/// A term broken over lines like a definition's body, first line unindented,
/// continuation lines indented by `indent` spaces.
std::string to_pretty_string(const Term& term, std::size_t indent, std::size_t width = 100);

}  // namespace p3at::verifier::pars
