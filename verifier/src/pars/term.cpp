#include "p3at/verifier/pars/term.hpp"

#include <utility>

namespace p3at::verifier::pars {

const char* to_string(Op op) {
  switch (op) {
    case Op::disabling: return "#";
    case Op::parallel: return "|";
    case Op::sequence: return ";";
  }
  return "?";
}

Term process(std::string name, std::vector<Expr> params, std::vector<std::string> in_ports,
             std::vector<std::string> out_ports) {
  Term t;
  t.kind = Term::Kind::process;
  t.name = std::move(name);
  t.params = std::move(params);
  t.in_ports = std::move(in_ports);
  t.out_ports = std::move(out_ports);
  return t;
}

Term compose(Op op, std::vector<Term> parts) {
  if (parts.size() == 1) return std::move(parts.front());
  Term t;
  t.kind = Term::Kind::composition;
  t.op = op;
  t.parts = std::move(parts);
  return t;
}

Term sequence(std::vector<Term> parts) { return compose(Op::sequence, std::move(parts)); }
Term parallel(std::vector<Term> parts) { return compose(Op::parallel, std::move(parts)); }
Term disabling(std::vector<Term> parts) { return compose(Op::disabling, std::move(parts)); }

Term internal_action() { return process(std::string(kInternalAction)); }

bool is_internal_action(const Term& term) {
  return term.is_process() && term.name == kInternalAction && term.params.empty() && term.in_ports.empty() &&
         term.out_ports.empty() && term.results.empty();
}

Term flatten(const Term& term) {
  if (term.is_process()) return term;
  std::vector<Term> parts;
  for (const Term& part : term.parts) {
    Term flat = flatten(part);
    if (!flat.is_process() && flat.op == term.op) {
      for (Term& inner : flat.parts) parts.push_back(std::move(inner));
    } else {
      parts.push_back(std::move(flat));
    }
  }
  return compose(term.op, std::move(parts));
}

void for_each_process(const Term& term, const std::function<void(const Term&)>& visit) {
  if (term.is_process()) {
    visit(term);
    return;
  }
  for (const Term& part : term.parts) for_each_process(part, visit);
}

const Definition* Program::find(std::string_view name) const {
  for (const Definition& d : definitions) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

const Term* tail_call(const Definition& definition) {
  const Term& body = definition.body;
  if (body.is_process() || body.op != Op::sequence || body.parts.size() < 2) return nullptr;
  const Term& last = body.parts.back();
  if (!last.is_process() || last.name != definition.name) return nullptr;
  // The period process P' (every part but the last) must not recurse itself.
  bool recursive = false;
  for (std::size_t i = 0; i + 1 < body.parts.size(); ++i) {
    for_each_process(body.parts[i], [&](const Term& p) { recursive = recursive || p.name == definition.name; });
  }
  return recursive ? nullptr : &last;
}

bool is_tail_recursive(const Definition& definition) { return tail_call(definition) != nullptr; }

}  // namespace p3at::verifier::pars
