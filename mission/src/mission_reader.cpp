#include "mission_reader.hpp"

#include <string>
#include <vector>

#include "robot_reader.hpp"

namespace p3at::mission::detail {
namespace {

const std::vector<std::string> kTopKeys{"mission", "criteria", "robots", "messages"};
const std::vector<std::string> kCriteriaKeys{"tmax_s", "rmax_m", "threshold", "abort_threshold", "abort_action"};
const std::vector<std::string> kMessageKeys{"name", "from", "to"};
constexpr double kMaxTmaxS = 86400.0;
constexpr double kMaxRmaxM = 1000.0;

struct MessageMarks {
  YAML::Mark name;
  YAML::Mark from;
};

Criteria read_criteria(const MapReader& c) {
  Criteria criteria;
  criteria.tmax_s = c.number("tmax_s", Range{0.0, kMaxTmaxS, true, false});
  criteria.rmax_m = c.number("rmax_m", Range{0.0, kMaxRmaxM, true, false});
  criteria.threshold = c.number("threshold", Range{0.0, 1.0, true, false});
  // Aborting a running mission at a probability the launch gate would accept makes no sense.
  criteria.abort_threshold = c.number_or("abort_threshold", Range{0.0, criteria.threshold}, 0.0);
  if (c.has("abort_action")) {
    const std::string action = c.string("abort_action");
    const auto parsed = abort_action_from_string(action);
    if (!parsed) {
      c.source().fail(c.value_mark("abort_action"), "unknown abort_action '" + show(action) +
                                                        "' (expected one of continue_and_warn, stop_and_notify)");
    }
    criteria.abort_action = *parsed;
  }
  return criteria;
}

std::vector<std::string> robot_names(const Mission& mission) {
  std::vector<std::string> names;
  for (const RobotSpec& r : mission.robots) names.push_back(r.name);
  return names;
}

std::size_t robot_ref(const Source& src, const YAML::Node& node, const YAML::Mark& mark, const Mission& mission,
                      std::string_view what) {
  if (!node.IsScalar()) src.fail(mark, "expected a robot name for " + std::string(what) + ", got " + describe(node));
  const auto index = mission.find_robot(node.Scalar());
  if (!index) {
    src.fail(mark, "unknown robot '" + show(node.Scalar()) + "' (expected one of " +
                       join_some(robot_names(mission)) + ")");
  }
  return *index;
}

Message read_message(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, const Mission& mission,
                     MessageMarks& marks) {
  const MapReader map(src, node, fallback, "for each message", "in message", "key", kMessageKeys);
  Message m;
  m.name = read_name(map, "name", "message");
  marks.name = map.value_mark("name");
  marks.from = map.value_mark("from");
  m.from = robot_ref(src, map.get("from"), marks.from, mission, "'from'");
  const YAML::Node to = map.sequence("to");
  if (to.size() == 0) src.fail(map.value_mark("to"), "message '" + m.name + "' has no recipients");
  std::vector<YAML::Mark> to_marks;
  for (const YAML::Node& item : to) {
    const YAML::Mark mark = item.IsNull() ? map.value_mark("to") : item.Mark();
    const std::size_t robot = robot_ref(src, item, mark, mission, "'to'");
    for (std::size_t i = 0; i < m.to.size(); ++i) {
      if (m.to[i] == robot) {
        src.fail(mark, "duplicate recipient '" + mission.robots[robot].name + "' of message '" + m.name +
                           "' (first at " + position(to_marks[i]) + ")");
      }
    }
    if (robot == m.from) {
      src.fail(mark, "message '" + m.name + "' lists its sender '" + mission.robots[robot].name + "' as a recipient");
    }
    m.to.push_back(robot);
    to_marks.push_back(mark);
  }
  return m;
}

bool is_recipient(const Message& m, std::size_t robot) {
  for (std::size_t r : m.to) {
    if (r == robot) return true;
  }
  return false;
}

// Every message a robot sends or waits for must be declared, with that robot
// as its sender or a recipient, and every declared sender must send it.
void check_team(const Source& src, const Mission& mission, const std::vector<RobotMarks>& robot_marks,
                const std::vector<MessageMarks>& message_marks) {
  for (std::size_t r = 0; r < mission.robots.size(); ++r) {
    const RobotSpec& robot = mission.robots[r];
    for (std::size_t s = 0; s < robot.states.size(); ++s) {
      const auto* notify = std::get_if<NotifyParams>(&robot.states[s].behavior);
      if (notify == nullptr) continue;
      const YAML::Mark& mark = robot_marks[r].notify_message[s];
      const auto m = mission.find_message(notify->message);
      if (!m) {
        src.fail(mark, "message '" + notify->message +
                           "' is not listed in messages (each message needs its sender and recipients there)");
      }
      if (mission.messages[*m].from != r) {
        src.fail(mark, "robot '" + robot.name + "' sends message '" + notify->message +
                           "', but messages lists robot '" + mission.robots[mission.messages[*m].from].name +
                           "' as its sender");
      }
    }
    for (std::size_t t = 0; t < robot.transitions.size(); ++t) {
      const auto* notified = std::get_if<NotifiedParams>(&robot.transitions[t].trigger);
      if (notified == nullptr) continue;
      const YAML::Mark& mark = robot_marks[r].trigger_message[t];
      const std::string prefix = "Notified on message '" + notified->message + "' that no teammate ever sends";
      const auto m = mission.find_message(notified->message);
      if (!m) src.fail(mark, prefix + " (it is not listed in messages)");
      const Message& message = mission.messages[*m];
      if (message.from == r) src.fail(mark, prefix + " (robot '" + robot.name + "' is its own sender)");
      if (!is_recipient(message, r)) {
        std::vector<std::string> to;
        for (std::size_t i : message.to) to.push_back(mission.robots[i].name);
        src.fail(mark, prefix + " to robot '" + robot.name + "' (messages lists its recipients as " +
                           join_some(to) + ")");
      }
    }
  }
  for (std::size_t m = 0; m < mission.messages.size(); ++m) {
    const Message& message = mission.messages[m];
    bool sent = false;
    for (const State& s : mission.robots[message.from].states) {
      const auto* notify = std::get_if<NotifyParams>(&s.behavior);
      sent = sent || (notify != nullptr && notify->message == message.name);
    }
    if (!sent) {
      src.fail(message_marks[m].from, "message '" + message.name + "' is listed as sent by robot '" +
                                          mission.robots[message.from].name + "', which has no Notify state for it");
    }
  }
}

}  // namespace

Mission read_mission(const Source& src, const YAML::Node& root) {
  const MapReader top(src, root, YAML::Mark(), "at the top level", "at the top level", "key", kTopKeys);
  Mission mission;

  const MapReader info = top.map("mission", "in mission", {"name", "description"});
  mission.name = read_name(info, "name", "mission");
  if (info.has("description")) mission.description = info.string("description");

  mission.criteria = read_criteria(top.map("criteria", "in criteria", kCriteriaKeys));

  const YAML::Node robots = top.sequence("robots");
  if (robots.size() == 0) src.fail(top.value_mark("robots"), "no robots (expected at least one)");
  std::vector<RobotMarks> robot_marks;
  for (const YAML::Node& item : robots) {
    RobotMarks marks;
    RobotSpec robot = read_robot(src, item, top.value_mark("robots"), marks);
    if (const auto first = mission.find_robot(robot.name)) {
      src.fail(marks.name, "duplicate robot name '" + robot.name + "' (first at " +
                               position(robot_marks[*first].name) + ")");
    }
    mission.robots.push_back(std::move(robot));
    robot_marks.push_back(std::move(marks));
  }

  std::vector<MessageMarks> message_marks;
  if (top.has("messages")) {
    for (const YAML::Node& item : top.sequence("messages")) {
      MessageMarks marks;
      Message message = read_message(src, item, top.value_mark("messages"), mission, marks);
      if (const auto first = mission.find_message(message.name)) {
        src.fail(marks.name, "duplicate message name '" + message.name + "' (first at " +
                                 position(message_marks[*first].name) + ")");
      }
      mission.messages.push_back(std::move(message));
      message_marks.push_back(marks);
    }
  }
  check_team(src, mission, robot_marks, message_marks);
  return mission;
}

}  // namespace p3at::mission::detail
