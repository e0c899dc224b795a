#include "p3at/verifier/pars/printer.hpp"

namespace p3at::verifier::pars {

namespace {

// Binding strength of the operators: ';' binds tightest, '#' loosest.
int strength(Op op) {
  switch (op) {
    case Op::disabling: return 1;
    case Op::parallel: return 2;
    case Op::sequence: return 3;
  }
  return 0;
}

// A part needs parentheses when it is a composition that binds no tighter
// than its parent: looser ones would regroup, and one of the same operator
// would merge into the parent's n-ary list.
bool needs_parens(const Term& part, Op parent) { return !part.is_process() && strength(part.op) <= strength(parent); }

void append_names(const std::vector<std::string>& names, std::string& out) {
  out += '(';
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += ", ";
    out += names[i];
  }
  out += ')';
}

// Name<params>(ins)(outs) -> (results); empty lists are left out.
void append_header(const std::string& name, const std::vector<std::string>& params, const std::vector<std::string>& ins,
                   const std::vector<std::string>& outs, const std::vector<std::string>& results, std::string& out) {
  out += name;
  if (!params.empty()) {
    out += '<';
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (i > 0) out += ", ";
      out += params[i];
    }
    out += '>';
  }
  // (ins)(outs); (ins) alone when there are no out ports.
  if (!ins.empty() || !outs.empty()) append_names(ins, out);
  if (!outs.empty()) append_names(outs, out);
  if (!results.empty()) {
    out += " -> ";
    append_names(results, out);
  }
}

std::string process_string(const Term& t) {
  std::vector<std::string> params;
  params.reserve(t.params.size());
  for (const Expr& p : t.params) {
    // A comparison at the top of a parameter would read as the closing '>'.
    params.push_back(p.kind == ExprKind::compare ? "(" + to_string(p) + ")" : to_string(p));
  }
  std::string out;
  append_header(t.name, params, t.in_ports, t.out_ports, t.results, out);
  return out;
}

void print(const Term& t, std::string& out) {
  if (t.is_process()) {
    out += process_string(t);
    return;
  }
  for (std::size_t i = 0; i < t.parts.size(); ++i) {
    if (i > 0) {
      out += ' ';
      out += to_string(t.op);
      out += ' ';
    }
    const bool parens = needs_parens(t.parts[i], t.op);
    if (parens) out += '(';
    print(t.parts[i], out);
    if (parens) out += ')';
  }
}

// Writes `t` starting at `column`: on one line if it fits in `width`, else one
// part per line, aligned, each but the last followed by the operator (a '#'
// must never start a line: there it would begin a comment).
void layout(const Term& t, std::size_t column, std::size_t width, std::string& out) {
  const std::string flat = to_string(t);
  if (t.is_process() || column + flat.size() <= width) {
    out += flat;
    return;
  }
  for (std::size_t i = 0; i < t.parts.size(); ++i) {
    if (i > 0) {
      out += '\n';
      out.append(column, ' ');
    }
    const Term& part = t.parts[i];
    // Broken over lines, every nested composition is parenthesised (as in the
    // paper's listing): redundant around a tighter operator, but it shows the nesting.
    if (!part.is_process()) {
      out += '(';
      layout(part, column + 1, width, out);
      out += ')';
    } else {
      layout(part, column, width, out);
    }
    if (i + 1 < t.parts.size()) {
      out += ' ';
      out += to_string(t.op);
    }
  }
}

}  // namespace

std::string to_string(const Term& term) {
  std::string out;
  print(term, out);
  return out;
}

std::string header_string(const Definition& d) {
  std::string out;
  append_header(d.name, d.params, d.in_ports, d.out_ports, d.results, out);
  return out;
}

std::string to_pretty_string(const Term& term, std::size_t indent, std::size_t width) {
  std::string out;
  layout(term, indent, width, out);
  return out;
}

std::string to_string(const Definition& d, std::size_t width) {
  std::string out;
  if (!d.comment.empty()) {
    std::size_t start = 0;
    while (true) {
      const std::size_t end = d.comment.find('\n', start);
      const std::string line = d.comment.substr(start, end == std::string::npos ? std::string::npos : end - start);
      out += line.empty() ? "#\n" : "# " + line + "\n";
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  const std::string header = header_string(d);
  const std::string flat = header + " = " + to_string(d.body);
  if (flat.size() <= width) {
    out += flat;
  } else {
    constexpr std::size_t kIndent = 4;
    out += header + " =\n";
    out.append(kIndent, ' ');
    layout(d.body, kIndent, width, out);
  }
  out += '\n';
  return out;
}

std::string to_string(const Program& program, std::size_t width) {
  std::string out;
  for (std::size_t i = 0; i < program.definitions.size(); ++i) {
    if (i > 0) out += '\n';
    out += to_string(program.definitions[i], width);
  }
  return out;
}

}  // namespace p3at::verifier::pars
