#include "p3at/mission/printer.hpp"

#include <array>
#include <charconv>
#include <sstream>

#include "yaml_reader.hpp"

namespace p3at::mission {
namespace {

using p3at::format_shortest;

// Names are plain when they cannot be mistaken for another YAML type.
bool needs_quotes(const std::string& name) {
  static const std::array<std::string_view, 11> kSpecial{"null", "true", "false", "yes", "no", "on",
                                                         "off",  "y",    "n",     "~",   ""};
  std::string lower;
  for (char c : name) lower += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  for (std::string_view special : kSpecial) {
    if (lower == special) return true;
  }
  return !is_valid_name(name);
}

// A YAML double-quoted scalar; every byte outside printable ASCII but UTF-8 text passes through.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      constexpr std::array<char, 17> kHex{"0123456789abcdef"};
      out += "\\x";
      out += kHex[byte >> 4U];
      out += kHex[byte & 0xFU];
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string name(const std::string& text) { return needs_quotes(text) ? quoted(text) : text; }

std::string point(const Point2& p) { return "[" + format_shortest(p.x_m) + ", " + format_shortest(p.y_m) + "]"; }

std::string behavior(const BehaviorParams& params) {
  std::ostringstream out;
  out << "behavior: " << to_string(kind_of(params));
  if (const auto* g = std::get_if<GoToGuardedParams>(&params)) {
    out << ", params: {goal: " << point(g->goal) << ", dropoff_m: " << format_shortest(g->dropoff_m)
        << ", dead_zone_m: " << format_shortest(g->dead_zone_m) << ", move_gain: " << format_shortest(g->move_gain)
        << ", avoid_gain: " << format_shortest(g->avoid_gain) << ", noise_gain: " << format_shortest(g->noise_gain)
        << ", sphere_m: " << format_shortest(g->sphere_m) << ", safety_margin_m: " << format_shortest(g->safety_margin_m)
        << ", noise_persistence_cycles: " << g->noise_persistence_cycles << "}";
  } else if (const auto* s = std::get_if<SpinParams>(&params)) {
    out << ", params: {rate_deg_s: " << format_shortest(s->rate_deg_s) << "}";
  } else if (const auto* n = std::get_if<NotifyParams>(&params)) {
    out << ", params: {message: " << name(n->message) << "}";
  }
  return out.str();
}

std::string trigger(const TriggerParams& params) {
  std::ostringstream out;
  out << "trigger: " << to_string(kind_of(params)) << ", params: {";
  if (const auto* a = std::get_if<AtGoalParams>(&params)) {
    out << "goal: " << point(a->goal) << ", radius_m: " << format_shortest(a->radius_m);
  } else if (const auto* h = std::get_if<HasTurnedParams>(&params)) {
    out << "angle_deg: " << format_shortest(h->angle_deg) << ", offset_deg: " << format_shortest(h->offset_deg);
  } else if (const auto* n = std::get_if<NotifiedParams>(&params)) {
    out << "message: " << name(n->message);
  } else if (const auto* m = std::get_if<MessageSentParams>(&params)) {
    out << "message: " << name(m->message);
  }
  out << "}";
  return out.str();
}

void robot(std::ostringstream& out, const RobotSpec& r) {
  out << "  - name: " << name(r.name) << "\n"
      << "    start: {x_m: " << format_shortest(r.start.x_m) << ", y_m: " << format_shortest(r.start.y_m)
      << ", theta_deg: " << format_shortest(r.start.theta_deg) << "}\n"
      << "    goal: " << point(r.goal) << "\n"
      << "    hal: " << quoted(r.hal_url) << "\n"
      << "    lcm: " << quoted(r.lcm_url) << "\n"
      << "    max_speed_mps: " << format_shortest(r.max_speed_mps) << "\n";
  if (r.initial < r.states.size()) out << "    initial: " << name(r.states[r.initial].name) << "\n";
  out << "    states:\n";
  for (const State& s : r.states) out << "      - {name: " << name(s.name) << ", " << behavior(s.behavior) << "}\n";
  if (r.transitions.empty()) return;
  out << "    transitions:\n";
  for (const Transition& t : r.transitions) {
    const auto state_name = [&](std::size_t i) { return i < r.states.size() ? name(r.states[i].name) : "\"?\""; };
    out << "      - {from: " << state_name(t.from) << ", to: " << state_name(t.to) << ", " << trigger(t.trigger)
        << "}\n";
  }
}

}  // namespace

std::string to_yaml(const Mission& m) {
  std::ostringstream out;
  out << "# Mission file in canonical form (docs/mission-format.md): every default written out.\n"
      << "mission:\n"
      << "  name: " << name(m.name) << "\n";
  if (!m.description.empty()) out << "  description: " << quoted(m.description) << "\n";
  out << "criteria:\n"
      << "  tmax_s: " << format_shortest(m.criteria.tmax_s) << "\n"
      << "  rmax_m: " << format_shortest(m.criteria.rmax_m) << "\n"
      << "  threshold: " << format_shortest(m.criteria.threshold) << "\n"
      << "  abort_threshold: " << format_shortest(m.criteria.abort_threshold) << "\n"
      << "  abort_action: " << to_string(m.criteria.abort_action) << "\n"
      << "robots:\n";
  for (const RobotSpec& r : m.robots) robot(out, r);
  if (m.messages.empty()) return out.str();
  out << "messages:\n";
  for (const Message& msg : m.messages) {
    out << "  - {name: " << name(msg.name) << ", from: "
        << (msg.from < m.robots.size() ? name(m.robots[msg.from].name) : "\"?\"") << ", to: [";
    for (std::size_t i = 0; i < msg.to.size(); ++i) {
      out << (i == 0 ? "" : ", ") << (msg.to[i] < m.robots.size() ? name(m.robots[msg.to[i]].name) : "\"?\"");
    }
    out << "]}\n";
  }
  return out.str();
}

}  // namespace p3at::mission
