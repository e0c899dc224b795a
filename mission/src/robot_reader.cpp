#include "robot_reader.hpp"

#include <deque>
#include <optional>
#include <string>

#include "params.hpp"

namespace p3at::mission::detail {
namespace {

const std::vector<std::string> kRobotKeys{"name",    "start",  "goal",       "hal", "lcm", "max_speed_mps",
                                          "initial", "states", "transitions"};
const std::vector<std::string> kStateKeys{"name", "behavior", "params"};
const std::vector<std::string> kTransitionKeys{"from", "to", "trigger", "params"};
const Range kThetaRange{-360.0, 360.0};
const Range kMaxSpeedRange{0.0, 2.0, true, false};

// "scheme://rest" (rest may be empty, as in LCM's memq://): the HAL and LCM
// pick the backend by scheme at run time; here we only check the shape.
bool looks_like_url(const std::string& text) {
  const auto sep = text.find("://");
  if (sep == std::string::npos || sep == 0) return false;
  if (!(text[0] >= 'a' && text[0] <= 'z')) return false;
  for (std::size_t i = 0; i < sep; ++i) {
    const char c = text[i];
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '.' || c == '-';
    if (!ok) return false;
  }
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte <= 0x20 || byte >= 0x7f) return false;  // URLs are printable ASCII without spaces
  }
  return true;
}

std::string read_url(const MapReader& robot, std::string_view key, std::string_view example) {
  std::string url = robot.string(key);
  if (!looks_like_url(url)) {
    robot.source().fail(robot.value_mark(key), "invalid URL '" + show(url) + "' for '" + std::string(key) +
                                                   "' (expected scheme://..., e.g. " + std::string(example) + ")");
  }
  return url;
}

std::vector<std::string> state_names(const RobotSpec& robot) {
  std::vector<std::string> names;
  for (const State& s : robot.states) names.push_back(s.name);
  return names;
}

// `what` starts the message: "transition from unknown state", ...
std::size_t state_ref(const MapReader& map, std::string_view key, const RobotSpec& robot, std::string_view what) {
  const std::string name = map.string(key);
  const auto index = robot.find_state(name);
  if (!index) {
    map.source().fail(map.value_mark(key), std::string(what) + " '" + show(name) +
                                               "' (robot '" + robot.name + "' has states " +
                                               join_some(state_names(robot)) + ")");
  }
  return *index;
}

State read_state(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, YAML::Mark& name_mark,
                 YAML::Mark& message_mark) {
  const MapReader map(src, node, fallback, "for each state", "in state", "key", kStateKeys);
  State state;
  state.name = read_name(map, "name", "state");
  name_mark = map.value_mark("name");
  const std::string behavior = map.string("behavior");
  const auto kind = behavior_kind_from_string(behavior);
  if (!kind) {
    src.fail(map.value_mark("behavior"),
             "unknown behavior '" + show(behavior) + "' (expected one of GoToGuarded, Spin, Stop, Notify)");
  }
  state.behavior = parse_behavior(map, *kind, map.value_mark("behavior"), message_mark);
  return state;
}

Transition read_transition(const Source& src, const YAML::Node& node, const YAML::Mark& fallback,
                           const RobotSpec& robot, YAML::Mark& message_mark) {
  const MapReader map(src, node, fallback, "for each transition", "in transition", "key", kTransitionKeys);
  Transition t;
  t.from = state_ref(map, "from", robot, "transition from unknown state");
  t.to = state_ref(map, "to", robot, "transition to unknown state");
  const std::string trigger = map.string("trigger");
  const auto kind = trigger_kind_from_string(trigger);
  if (!kind) {
    src.fail(map.value_mark("trigger"),
             "unknown trigger '" + show(trigger) + "' (expected one of AtGoal, HasTurned, Notified, MessageSent)");
  }
  t.trigger = parse_trigger(map, *kind, map.value_mark("trigger"), robot, robot.states[t.from], message_mark);
  return t;
}

void read_states(const MapReader& map, RobotSpec& robot, RobotMarks& marks, std::vector<YAML::Mark>& name_marks) {
  const YAML::Node states = map.sequence("states");
  if (states.size() == 0) {
    map.source().fail(map.value_mark("states"), "robot '" + robot.name + "' has no states");
  }
  for (const YAML::Node& item : states) {
    YAML::Mark name_mark;
    YAML::Mark message_mark;
    State state = read_state(map.source(), item, map.value_mark("states"), name_mark, message_mark);
    if (const auto first = robot.find_state(state.name)) {
      map.source().fail(name_mark, "duplicate state name '" + state.name + "' in robot '" + robot.name +
                                       "' (first at " + position(name_marks[*first]) + ")");
    }
    name_marks.push_back(name_mark);
    robot.states.push_back(std::move(state));
    marks.notify_message.push_back(message_mark);
  }
}

// Every state must be reachable from the initial one, and the FSA must be able to finish.
void check_graph(const MapReader& map, const RobotSpec& robot, const std::vector<YAML::Mark>& name_marks) {
  std::vector<bool> seen(robot.states.size(), false);
  std::deque<std::size_t> queue{robot.initial};
  seen[robot.initial] = true;
  while (!queue.empty()) {
    const std::size_t s = queue.front();
    queue.pop_front();
    for (std::size_t t : robot.states[s].outgoing) {
      const std::size_t next = robot.transitions[t].to;
      if (!seen[next]) {
        seen[next] = true;
        queue.push_back(next);
      }
    }
  }
  for (std::size_t i = 0; i < robot.states.size(); ++i) {
    if (!seen[i]) {
      map.source().fail(name_marks[i], "state '" + robot.states[i].name + "' of robot '" + robot.name +
                                           "' is unreachable from its initial state '" +
                                           robot.initial_state().name + "'");
    }
  }
  for (std::size_t i = 0; i < robot.states.size(); ++i) {
    if (robot.is_final(i)) return;
  }
  // Only reached with transitions present: without any, every state is final.
  map.source().fail(map.key_mark("transitions"), "robot '" + robot.name +
                                                     "' has no final state (a state with no outgoing "
                                                     "transitions), so its FSA can never finish");
}

std::string point_text(const Point2& p) { return "[" + format_shortest(p.x_m) + ", " + format_shortest(p.y_m) + "]"; }

// Rmax is measured from each robot's goal. Unless given, it is where the
// mission's last moves lead: the goal of the GoToGuarded states met first when
// walking back from every final state, which must agree. A robot that never
// drives to a goal must end where it started.
Point2 implied_goal(const MapReader& map, const RobotSpec& robot) {
  std::vector<bool> seen(robot.states.size(), false);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < robot.states.size(); ++i) {
    if (robot.is_final(i)) {
      seen[i] = true;
      queue.push_back(i);
    }
  }
  std::optional<Point2> goal;
  while (!queue.empty()) {
    const std::size_t s = queue.front();
    queue.pop_front();
    if (const auto* go = std::get_if<GoToGuardedParams>(&robot.states[s].behavior)) {
      if (goal && !(*goal == go->goal)) {
        map.source().fail(map.value_mark("name"), "robot '" + robot.name + "' ends at more than one GoToGuarded goal (" +
                                                      point_text(*goal) + " and " + point_text(go->goal) +
                                                      "); give its goal explicitly with 'goal: [x_m, y_m]'");
      }
      goal = go->goal;
      continue;  // the last move on this path
    }
    for (const Transition& t : robot.transitions) {
      if (t.to == s && !seen[t.from]) {
        seen[t.from] = true;
        queue.push_back(t.from);
      }
    }
  }
  return goal ? *goal : Point2{robot.start.x_m, robot.start.y_m};
}

}  // namespace

RobotSpec read_robot(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, RobotMarks& marks) {
  const MapReader map(src, node, fallback, "for each robot", "in robot", "key", kRobotKeys);
  RobotSpec robot;
  robot.name = read_name(map, "name", "robot");
  marks.name = map.value_mark("name");

  const MapReader start = map.map("start", "in start", {"x_m", "y_m", "theta_deg"});
  robot.start.x_m = start.number("x_m", kCoordinateRange);
  robot.start.y_m = start.number("y_m", kCoordinateRange);
  robot.start.theta_deg = start.number_or("theta_deg", kThetaRange, 0.0);
  const bool explicit_goal = map.has("goal");
  if (explicit_goal) robot.goal = read_point(map, "goal", kCoordinateRange);

  robot.hal_url = read_url(map, "hal", "tcp://127.0.0.1:8101");
  if (map.has("lcm")) robot.lcm_url = read_url(map, "lcm", kDefaultLcmUrl);
  robot.max_speed_mps = map.number_or("max_speed_mps", kMaxSpeedRange, kDefaultMaxSpeedMps);

  std::vector<YAML::Mark> name_marks;
  read_states(map, robot, marks, name_marks);
  if (map.has("initial")) robot.initial = state_ref(map, "initial", robot, "unknown initial state");

  if (map.has("transitions")) {
    for (const YAML::Node& item : map.sequence("transitions")) {
      YAML::Mark message_mark;
      robot.transitions.push_back(read_transition(src, item, map.value_mark("transitions"), robot, message_mark));
      marks.trigger_message.push_back(message_mark);
    }
  }
  for (std::size_t t = 0; t < robot.transitions.size(); ++t) {
    robot.states[robot.transitions[t].from].outgoing.push_back(t);
  }
  check_graph(map, robot, name_marks);
  if (!explicit_goal) robot.goal = implied_goal(map, robot);
  return robot;
}

}  // namespace p3at::mission::detail

