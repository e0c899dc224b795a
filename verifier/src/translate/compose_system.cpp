// System composition (the seed paper's section IV.C): match the port
// operations of Sys's components, O(np·nio) with a map from each out port to
// its writer, then follow the connections to the flow function f(u) of the
// tail-recursive components, O(nv·np·nio).

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"

namespace p3at::verifier {

namespace {

using pars::Definition;
using pars::Expr;
using pars::Term;

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// What one period of a TR component does with its ports.
struct PeriodOps {
  std::map<std::string, std::string> formal_port;   // formal port -> actual port
  std::map<std::string, Expr> formal_param;         // formal parameter -> actual expression
  std::map<std::string, Expr> writes;               // actual port -> expression (in formals and read variables)
  std::map<std::string, std::string> reads;         // variable -> actual port
};

class Composer {
 public:
  Composer(const pars::Program& program, const Definition& sys) : program_(program), sys_(sys) {}

  Result<SystemComposition> run() {
    SystemComposition out;
    out.system = sys_.name;
    out.parameters = sys_.params;
    if (auto status = collect_components(out); !status) return status.error();
    if (auto status = match_ports(out); !status) return status.error();
    if (auto status = flow_function(out); !status) return status.error();
    return out;
  }

 private:
  Status collect_components(SystemComposition& out) {
    std::vector<const Term*> calls;
    const Term& body = sys_.body;
    if (body.is_process()) {
      calls.push_back(&body);
    } else if (body.op != pars::Op::parallel) {
      return make_error(Error::Code::invalid_argument,
                        "the body of " + sys_.name + " must be a parallel composition of components, not a '" +
                            pars::to_string(body.op) + "' composition: " + pars::to_string(body));
    } else {
      for (std::size_t i = 0; i < body.parts.size(); ++i) {
        if (!body.parts[i].is_process()) {
          return make_error(Error::Code::invalid_argument,
                            "component " + std::to_string(i + 1) + " of " + sys_.name + " is a '" +
                                pars::to_string(body.parts[i].op) + "' composition (" + pars::to_string(body.parts[i]) +
                                "); each component must be one process call");
        }
        calls.push_back(&body.parts[i]);
      }
    }
    std::map<std::string, int> uses;
    for (const Term* c : calls) ++uses[c->name];
    for (std::size_t i = 0; i < calls.size(); ++i) {
      SystemComponent component;
      component.call = *calls[i];
      component.label = calls[i]->name;
      if (uses[calls[i]->name] > 1) {
        component.label += calls[i]->params.empty() ? "[" + std::to_string(i + 1) + "]"
                                                    : "<" + pars::to_string(calls[i]->params.front()) + ">";
      }
      const Definition* def = program_.find(calls[i]->name);
      component.defined = def != nullptr;
      component.tail_recursive = def != nullptr && pars::is_tail_recursive(*def);
      out.components.push_back(std::move(component));
    }
    return {};
  }

  Status match_ports(SystemComposition& out) {
    writer_.clear();
    for (std::size_t i = 0; i < out.components.size(); ++i) {
      for (const std::string& port : out.components[i].call.out_ports) {
        const auto [it, inserted] = writer_.emplace(port, i);
        if (!inserted) {
          const std::string first = out.components[it->second].label;
          return make_error(Error::Code::invalid_argument,
                            it->second == i
                                ? first + " lists out port '" + port + "' twice"
                                : "port '" + port + "' is written by both " + first + " and " + out.components[i].label +
                                      " (each port needs exactly one writer)");
        }
      }
    }
    for (std::size_t r = 0; r < out.components.size(); ++r) {
      const SystemComponent& reader = out.components[r];
      for (const std::string& port : reader.call.in_ports) {
        const auto it = writer_.find(port);
        if (it == writer_.end()) {
          std::vector<std::string> written;
          for (const auto& [p, w] : writer_) written.push_back(p);
          std::sort(written.begin(), written.end());
          return make_error(Error::Code::invalid_argument,
                            "port '" + port + "' read by " + reader.label + " (" + pars::to_string(reader.call) +
                                ") is written by no component of " + sys_.name + " (out ports: " +
                                (written.empty() ? "none" : list_names(written)) + ")");
        }
        if (it->second == r) {
          return make_error(Error::Code::invalid_argument,
                            reader.label + " reads its own out port '" + port +
                                "' (an in port must be written by another component)");
        }
        out.connections.push_back(PortConnection{port, it->second, r});
      }
    }
    return {};
  }

  // The In/Out operations of one TR component's period, with ports made actual.
  Status period_ops(const SystemComponent& component, const Definition& def, PeriodOps& ops) {
    const Term& call = component.call;
    if (call.params.size() != def.params.size()) {
      return make_error(Error::Code::invalid_argument,
                        component.label + " passes " + std::to_string(call.params.size()) + " parameters to " +
                            def.name + ", which takes " + std::to_string(def.params.size()) + " (" +
                            list_names(def.params) + ")");
    }
    const bool declares_ports = !def.in_ports.empty() || !def.out_ports.empty();
    if (declares_ports &&
        (call.in_ports.size() != def.in_ports.size() || call.out_ports.size() != def.out_ports.size())) {
      return make_error(Error::Code::invalid_argument,
                        component.label + " connects " + std::to_string(call.in_ports.size()) + " in and " +
                            std::to_string(call.out_ports.size()) + " out ports to " + pars::header_string(def) +
                            ", which has " + std::to_string(def.in_ports.size()) + " and " +
                            std::to_string(def.out_ports.size()));
    }
    for (std::size_t i = 0; i < def.params.size(); ++i) ops.formal_param[def.params[i]] = call.params[i];
    if (declares_ports) {
      for (std::size_t i = 0; i < def.in_ports.size(); ++i) ops.formal_port[def.in_ports[i]] = call.in_ports[i];
      for (std::size_t i = 0; i < def.out_ports.size(); ++i) ops.formal_port[def.out_ports[i]] = call.out_ports[i];
    }
    const auto actual = [&](const std::string& formal) {
      const auto it = ops.formal_port.find(formal);
      return it == ops.formal_port.end() ? formal : it->second;
    };
    Status status;
    for (std::size_t part = 0; part + 1 < def.body.parts.size() && status; ++part) {
      pars::for_each_process(def.body.parts[part], [&](const Term& p) {
        if (!status || (p.name != "In" && p.name != "Out")) return;
        if (p.params.size() != 2 || p.params[0].kind != pars::ExprKind::name ||
            (p.name == "In" && p.params[1].kind != pars::ExprKind::name)) {
          status = make_error(Error::Code::invalid_argument,
                              "in " + def.name + ", " + pars::to_string(p) + " is not a port operation (expected " +
                                  (p.name == "In" ? "In<port, variable>" : "Out<port, expression>") + ")");
          return;
        }
        const std::string& port = p.params[0].name;
        if (declares_ports && ops.formal_port.count(port) == 0) {
          status = make_error(Error::Code::invalid_argument, "in " + def.name + ", " + pars::to_string(p) +
                                                                 " uses '" + port + "', which is not one of its ports");
          return;
        }
        if (p.name == "In") {
          ops.reads[p.params[1].name] = actual(port);
        } else {
          ops.writes[actual(port)] = p.params[1];
        }
      });
    }
    return status;
  }

  Status flow_function(SystemComposition& out) {
    ops_.assign(out.components.size(), PeriodOps{});
    for (std::size_t i = 0; i < out.components.size(); ++i) {
      if (!out.components[i].tail_recursive) continue;
      const Definition& def = *program_.find(out.components[i].call.name);
      if (auto status = period_ops(out.components[i], def, ops_[i]); !status) return status;
    }
    for (std::size_t i = 0; i < out.components.size(); ++i) {
      if (!out.components[i].tail_recursive) continue;
      const Definition& def = *program_.find(out.components[i].call.name);
      const Term& tail = *pars::tail_call(def);
      if (tail.params.size() != def.params.size()) {
        return make_error(Error::Code::invalid_argument,
                          def.name + " recurses with " + std::to_string(tail.params.size()) +
                              " parameters but takes " + std::to_string(def.params.size()));
      }
      for (std::size_t k = 0; k < def.params.size(); ++k) {
        FlowUpdate update;
        update.component = i;
        update.parameter = def.params[k];
        update.initial = out.components[i].call.params[k];
        std::set<std::string> visiting;
        update.update = resolve(out, i, tail.params[k], visiting, update.ports);
        out.flow.push_back(std::move(update));
      }
    }
    return {};
  }

  // An expression of component c in the system's parameters: its formals by
  // their actual values, the variables it reads by what their ports carry.
  Expr resolve(const SystemComposition& sys, std::size_t c, const Expr& e, std::set<std::string>& visiting,
               std::vector<std::string>& ports) {
    const PeriodOps& ops = ops_[c];
    return pars::substitute(e, [&](const std::string& n) -> std::optional<Expr> {
      if (const auto read = ops.reads.find(n); read != ops.reads.end()) {
        return port_value(sys, read->second, visiting, ports);
      }
      if (const auto param = ops.formal_param.find(n); param != ops.formal_param.end()) return param->second;
      return std::nullopt;
    });
  }

  Expr port_value(const SystemComposition& sys, const std::string& port, std::set<std::string>& visiting,
                  std::vector<std::string>& ports) {
    if (std::find(ports.begin(), ports.end(), port) == ports.end()) ports.push_back(port);
    const std::size_t w = writer_.at(port);
    const auto write = ops_[w].writes.find(port);
    // A cycle of same-period reads, or a writer whose output is not an Out
    // expression: the port's name stands for its value.
    if (!sys.components[w].tail_recursive || write == ops_[w].writes.end() || visiting.count(port) > 0) {
      return pars::name(port);
    }
    visiting.insert(port);
    Expr value = resolve(sys, w, write->second, visiting, ports);
    visiting.erase(port);
    return value;
  }

  const pars::Program& program_;
  const Definition& sys_;
  std::unordered_map<std::string, std::size_t> writer_;
  std::vector<PeriodOps> ops_;
};

}  // namespace

std::vector<std::size_t> SystemComposition::feeders(std::size_t index) const {
  std::vector<std::size_t> out;
  for (const PortConnection& c : connections) {
    if (c.reader == index && std::find(out.begin(), out.end(), c.writer) == out.end()) out.push_back(c.writer);
  }
  return out;
}

const FlowUpdate* SystemComposition::find_flow(std::string_view component_label, std::string_view parameter) const {
  for (const FlowUpdate& f : flow) {
    if (components[f.component].label == component_label && f.parameter == parameter) return &f;
  }
  return nullptr;
}

Result<SystemComposition> compose_system(const pars::Program& program, std::string_view system) {
  const Definition* sys = program.find(system);
  if (sys == nullptr) {
    std::vector<std::string> defined;
    for (const Definition& d : program.definitions) defined.push_back(d.name);
    return make_error(Error::Code::not_found, "no definition of '" + std::string(system) + "' in the program (it defines " +
                                                  (defined.empty() ? "nothing" : list_names(defined)) + ")");
  }
  return Composer(program, *sys).run();
}

std::string to_string(const SystemComposition& c) {
  std::string out = c.system;
  if (!c.parameters.empty()) out += "<" + list_names(c.parameters) + ">";
  out += ": " + std::to_string(c.components.size()) + " components, " + std::to_string(c.connections.size()) +
         " connections\n";
  for (std::size_t i = 0; i < c.components.size(); ++i) {
    const SystemComponent& comp = c.components[i];
    out += "  " + comp.label + (comp.tail_recursive ? " (tail-recursive)" : comp.defined ? "" : " (basic)") + "\n";
    for (const PortConnection& conn : c.connections) {
      if (conn.reader == i) out += "    <- " + conn.port + " from " + c.components[conn.writer].label + "\n";
    }
  }
  if (!c.flow.empty()) out += "flow function f(u):\n";
  for (const FlowUpdate& f : c.flow) {
    out += "  " + c.components[f.component].label + "." + f.parameter + " <- " + pars::to_string(f.update);
    if (!f.ports.empty()) out += "   (via " + list_names(f.ports) + ")";
    out += "\n";
  }
  return out;
}

}  // namespace p3at::verifier
