// Reading criterion files (docs/pars.md, "Criterion files"): a header line,
// a PARS network of Delay and At processes, and one constraint per line. The
// PARS tokenizer gives every token its line and column, so each problem is
// reported where it is.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "criteria/events.hpp"
#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "pars/parser_impl.hpp"

namespace p3at::verifier {

namespace {

using pars::detail::Parser;
using pars::detail::Tok;
using pars::detail::Token;

constexpr std::streamoff kMaxFileBytes = 1 << 20;

bool is_word(const Token& t, std::string_view word) { return t.kind == Tok::name && t.text == word; }

bool is_reserved(std::string_view n) { return n == "P" || n == "and"; }

// The network's processes must be Delay<t> and At<robot, p>, each variable used once.
detail::VariableKinds check_network(const Parser& parser, std::size_t first, const pars::Term& network) {
  std::vector<const pars::Term*> processes;
  pars::for_each_process(network, [&](const pars::Term& p) { processes.push_back(&p); });
  detail::VariableKinds kinds;
  std::map<std::string, const Token*> first_use;
  std::map<std::string, const Token*> robots;
  const auto& located = parser.processes();
  for (std::size_t i = 0; i < processes.size() && first + i < located.size(); ++i) {
    const pars::Term& p = *processes[i];
    const Token& at = *located[first + i].at;
    const std::string text = pars::to_string(p);
    if (!p.in_ports.empty() || !p.out_ports.empty() || !p.results.empty()) {
      parser.fail(at, "a criterion's processes have no ports or results, got '" + text + "'");
    }
    const bool delay = p.name == "Delay";
    if (!delay && p.name != "At") {
      parser.fail(at, "unknown process '" + p.name +
                          "' in a criterion network (expected Delay<time variable> or At<robot, position variable>)");
    }
    const std::size_t arity = delay ? 1 : 2;
    bool names_only = p.params.size() == arity;
    for (const pars::Expr& e : p.params) names_only = names_only && e.kind == pars::ExprKind::name;
    if (!names_only) {
      parser.fail(at, delay ? "Delay takes one time variable, Delay<t>, got '" + text + "'"
                            : "At takes a robot and a position variable, At<robot, p>, got '" + text + "'");
    }
    if (!delay) robots.emplace(p.params[0].name, &at);
    const std::string& var = p.params.back().name;
    if (is_reserved(var)) parser.fail(at, "'" + var + "' is reserved (P(...) and 'and' in constraints); rename the variable");
    const auto [it, inserted] = first_use.emplace(var, &at);
    if (!inserted) {
      parser.fail(at, "variable '" + var + "' appears twice in the network (first at " +
                          std::to_string(it->second->line) + ":" + std::to_string(it->second->column) + ")");
    }
    kinds[var] = delay ? detail::VariableKind::time : detail::VariableKind::position;
  }
  for (const auto& [robot, at] : robots) {
    if (kinds.count(robot) > 0) parser.fail(*at, "'" + robot + "' names both a robot and a variable");
  }
  return kinds;
}

Comparison read_comparison(Parser& parser, const detail::VariableKinds& kinds) {
  const Token& start = parser.peek();
  Comparison c;
  c.line = start.line;
  c.column = start.column;
  c.left.push_back(parser.expr());
  while (parser.accept(Tok::comma)) c.left.push_back(parser.expr());
  const Token& op = parser.peek();
  if (!pars::detail::compare_op(op.kind, c.op)) {
    parser.fail(op, "expected a comparison (<, <=, > or >=), got " + Parser::describe(op));
  }
  parser.next();
  c.right = parser.expr();
  std::vector<detail::Event> events;
  std::string problem;
  if (!detail::classify(c, kinds, events, problem)) parser.fail(start, problem);
  return c;
}

Constraint read_constraint(Parser& parser, const detail::VariableKinds& kinds) {
  const Token& start = parser.peek();
  if (!start.first_on_line) parser.fail(start, "each constraint goes on its own line");
  Constraint k;
  k.line = start.line;
  k.column = start.column;
  if (is_word(start, "P") && parser.peek(1).kind == Tok::lparen) {
    parser.next();
    parser.next();
    k.probabilistic = true;
    k.events.push_back(read_comparison(parser, kinds));
    while (is_word(parser.peek(), "and")) {
      parser.next();
      k.events.push_back(read_comparison(parser, kinds));
    }
    parser.expect(Tok::rparen, "'and' or ')' to close P(...)");
    const Token& op = parser.peek();
    if (op.kind == Tok::greater) {
      k.bound_op = pars::CompareOp::greater;
    } else if (op.kind == Tok::greater_equal) {
      k.bound_op = pars::CompareOp::greater_equal;
    } else if (op.kind == Tok::less || op.kind == Tok::less_equal) {
      parser.fail(op, "a probability constraint is a lower bound, P(...) > x or P(...) >= x "
                      "(for an upper bound, negate the event inside P)");
    } else {
      parser.fail(op, "expected '>' or '>=' and a probability after P(...), got " + Parser::describe(op));
    }
    parser.next();
    const Token& at_bound = parser.peek();
    const auto bound = pars::constant_value(parser.expr());
    if (!bound || *bound < 0.0 || *bound > 1.0) {
      parser.fail(at_bound, "expected a probability between 0 and 1, got " + Parser::describe(at_bound));
    }
    k.bound = *bound;
  } else {
    k.events.push_back(read_comparison(parser, kinds));
  }
  const Token& after = parser.peek();
  if (after.kind != Tok::end && !after.first_on_line) {
    parser.fail(after, "expected the end of the line after the constraint, got " + Parser::describe(after));
  }
  return k;
}

Criterion read_criterion(Parser& parser) {
  Criterion c;
  c.source = parser.source();
  const Token& keyword = parser.peek();
  if (!is_word(keyword, "criterion")) {
    parser.fail(keyword, "expected 'criterion NAME' to begin the criterion, got " + Parser::describe(keyword));
  }
  parser.next();
  const Token& name = parser.peek();
  if (name.kind != Tok::name || name.first_on_line) {
    parser.fail(name, "expected the criterion's name after 'criterion', got " + Parser::describe(name));
  }
  c.name = std::string(name.text);
  parser.next();
  const Token& network = parser.peek();
  if (!is_word(network, "network") || !network.first_on_line) {
    parser.fail(network, "expected 'network' and the criterion's process network on a new line, got " +
                             Parser::describe(network));
  }
  parser.next();
  const std::size_t first = parser.processes().size();
  c.network = parser.term();
  const detail::VariableKinds kinds = check_network(parser, first, c.network);
  if (parser.at(Tok::end)) return c;
  const Token& constraints = parser.peek();
  if (!is_word(constraints, "constraints") || !constraints.first_on_line) {
    parser.fail(constraints, "unexpected " + Parser::describe(constraints) +
                                 " after the network (expected an operator ';', '|' or '#', or 'constraints' on a "
                                 "new line)");
  }
  parser.next();
  while (!parser.at(Tok::end)) c.constraints.push_back(read_constraint(parser, kinds));
  return c;
}

}  // namespace

Criterion parse_criterion(std::string_view text, const std::string& source_name) {
  try {
    Parser parser(text, source_name);
    return read_criterion(parser);
  } catch (const pars::ParseError& e) {
    throw CriterionError(e.source(), e.line(), e.column(), e.detail());
  }
}

Criterion load_criterion_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw CriterionError(path, 0, 0, "cannot open criterion file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CriterionError(path, 0, 0, std::string("cannot open criterion file: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size > kMaxFileBytes) {
    throw CriterionError(path, 0, 0, "criterion file too large (" + std::to_string(size) + " bytes, limit " +
                                         std::to_string(kMaxFileBytes) + ")");
  }
  in.seekg(0, std::ios::beg);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw CriterionError(path, 0, 0, "cannot read criterion file");
  return parse_criterion(text.str(), path);
}

}  // namespace p3at::verifier
