// A valid mission loads with every default resolved and every index right.

#include <doctest/doctest.h>


#include <filesystem>
#include <fstream>

#include "fixtures.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/mission/mission.hpp"
#include "scratch.hpp"

using namespace p3at::mission;
using p3at::mission::test::kBoundingOverwatch;
using p3at::mission::test::kRelay;
using p3at::mission::test::replace_once;

TEST_CASE("the relay mission loads with every default resolved") {
  const Mission m = parse_mission(kRelay, "relay.yaml");
  CHECK(m.name == "relay");
  CHECK(m.description.empty());
  CHECK(m.criteria.tmax_s == 60.0);
  CHECK(m.criteria.rmax_m == 0.5);
  CHECK(m.criteria.threshold == 0.8);
  CHECK(m.criteria.abort_threshold == 0.0);
  CHECK(m.criteria.abort_action == AbortAction::continue_and_warn);
  REQUIRE(m.robots.size() == 2);

  const RobotSpec& r1 = m.robots[0];
  CHECK(r1.name == "robot1");
  CHECK(r1.start == Pose2{1.0, 1.0, 0.0});
  CHECK(r1.goal == Point2{3.0, 1.0});  // the GoToGuarded before its final state
  CHECK(r1.hal_url == "tcp://127.0.0.1:8101");
  CHECK(r1.lcm_url == "udpm://239.255.76.67:7667?ttl=0");
  CHECK(r1.max_speed_mps == 0.3);
  CHECK(r1.initial == 0);
  CHECK(r1.initial_state().name == "drive");

  REQUIRE(r1.states.size() == 3);
  REQUIRE(r1.states[0].kind() == BehaviorKind::go_to_guarded);
  const auto& drive = std::get<GoToGuardedParams>(r1.states[0].behavior);
  CHECK(drive.goal == Point2{3.0, 1.0});
  CHECK(drive.dropoff_m == 0.5);  // given
  CHECK(drive.dead_zone_m == 0.05);  // defaults from here on
  CHECK(drive.move_gain == 1.0);
  CHECK(drive.avoid_gain == 1.0);
  CHECK(drive.noise_gain == 0.1);
  CHECK(drive.sphere_m == 1.0);
  CHECK(drive.safety_margin_m == 0.25);
  CHECK(drive.noise_persistence_cycles == 10);
  CHECK(std::get<NotifyParams>(r1.states[1].behavior).message == "r1_done");
  CHECK(r1.states[2].kind() == BehaviorKind::stop);

  REQUIRE(r1.transitions.size() == 2);
  const auto& at_goal = std::get<AtGoalParams>(r1.transitions[0].trigger);
  CHECK(at_goal.goal == Point2{3.0, 1.0});  // from the source state's GoToGuarded
  CHECK(at_goal.radius_m == 0.2);
  CHECK(std::get<MessageSentParams>(r1.transitions[1].trigger).message == "r1_done");  // from the Notify

  const RobotSpec& r2 = m.robots[1];
  CHECK(r2.start == Pose2{1.0, 2.0, 0.0});  // theta_deg defaults to 0
  CHECK(r2.goal == Point2{3.0, 2.0});
  CHECK(r2.initial_state().name == "wait");
  CHECK(std::get<NotifiedParams>(r2.transitions[0].trigger).message == "r1_done");
  CHECK(std::get<AtGoalParams>(r2.transitions[1].trigger).goal == Point2{3.0, 2.0});
}

TEST_CASE("state and transition indices, final states and lookups") {
  const Mission m = parse_mission(kRelay, "relay.yaml");
  const RobotSpec& r1 = m.robots[0];
  CHECK(r1.find_state("drive") == 0u);
  CHECK(r1.find_state("tell") == 1u);
  CHECK(r1.find_state("done") == 2u);
  CHECK_FALSE(r1.find_state("wait").has_value());

  CHECK(r1.transitions[0].from == 0);
  CHECK(r1.transitions[0].to == 1);
  CHECK(r1.transitions[0].kind() == TriggerKind::at_goal);
  CHECK(r1.transitions[1].from == 1);
  CHECK(r1.transitions[1].to == 2);
  CHECK(r1.transitions[1].kind() == TriggerKind::message_sent);
  CHECK(r1.states[0].outgoing == std::vector<std::size_t>{0});
  CHECK(r1.states[1].outgoing == std::vector<std::size_t>{1});
  CHECK(r1.states[2].outgoing.empty());

  CHECK_FALSE(r1.is_final(0));
  CHECK_FALSE(r1.is_final(1));
  CHECK(r1.is_final(2));
  CHECK_FALSE(r1.is_final(3));  // out of range is not final
  CHECK_FALSE(r1.is_final(static_cast<std::size_t>(-1)));

  CHECK(m.find_robot("robot2") == 1u);
  CHECK_FALSE(m.find_robot("robot3").has_value());
  REQUIRE(m.messages.size() == 1);
  CHECK(m.find_message("r1_done") == 0u);
  CHECK_FALSE(m.find_message("r2_done").has_value());
  CHECK(m.messages[0].from == 0);
  CHECK(m.messages[0].to == std::vector<std::size_t>{1});
}

TEST_CASE("the implied goal is the last move before the final state, not the last state listed") {
  std::string text = replace_once(kRelay, "      - {name: finished, behavior: Stop}\n",
                                  "      - {name: finished, behavior: Stop}\n"
                                  "      - {name: detour, behavior: GoToGuarded, params: {goal: [9, 9]}}\n");
  text = replace_once(text, "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
                      "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}\n"
                      "      - {from: wait, to: detour, trigger: HasTurned, params: {angle_deg: 30}}\n"
                      "      - {from: detour, to: wait, trigger: AtGoal, params: {radius_m: 0.5}}");
  const Mission m = parse_mission(text, "t.yaml");
  CHECK(m.robots[1].goal == Point2{3.0, 2.0});
}

TEST_CASE("final states reached from different goals need an explicit robot goal") {
  std::string text = replace_once(kRelay, "      - {name: finished, behavior: Stop}\n",
                                  "      - {name: finished, behavior: Stop}\n"
                                  "      - {name: detour, behavior: GoToGuarded, params: {goal: [9, 9]}}\n"
                                  "      - {name: parked, behavior: Stop}\n");
  text = replace_once(text, "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
                      "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}\n"
                      "      - {from: wait, to: detour, trigger: HasTurned, params: {angle_deg: 30}}\n"
                      "      - {from: detour, to: parked, trigger: AtGoal, params: {radius_m: 0.5}}");
  CHECK(test::error_of(text) == "t.yaml:" + test::loc(text, "robot2") +
                                    ": robot 'robot2' ends at more than one GoToGuarded goal ([3, 2] and [9, 9]); "
                                    "give its goal explicitly with 'goal: [x_m, y_m]'");
  text = replace_once(text, "    hal: tcp://127.0.0.1:8102\n", "    goal: [3, 2]\n    hal: tcp://127.0.0.1:8102\n");
  CHECK(parse_mission(text, "t.yaml").robots[1].goal == Point2{3.0, 2.0});
}

TEST_CASE("an explicit robot goal overrides the implied one") {
  const std::string text =
      replace_once(kRelay, "    hal: tcp://127.0.0.1:8102\n", "    goal: [2.5, 2.0]\n    hal: tcp://127.0.0.1:8102\n");
  const Mission m = parse_mission(text, "t.yaml");
  CHECK(m.robots[1].goal == Point2{2.5, 2.0});
  CHECK(m.robots[0].goal == Point2{3.0, 1.0});
}

TEST_CASE("several transitions out of one state keep file order in outgoing") {
  const std::string text = replace_once(kRelay, "      - {from: drive2, to: finished,",
                                        "      - {from: wait, to: finished, trigger: HasTurned, params: {angle_deg: 45}}\n"
                                        "      - {from: drive2, to: finished,");
  const Mission m = parse_mission(text, "t.yaml");
  const RobotSpec& r2 = m.robots[1];
  REQUIRE(r2.transitions.size() == 3);
  CHECK(r2.states[0].outgoing == std::vector<std::size_t>{0, 1});
  CHECK(r2.transitions[1].kind() == TriggerKind::has_turned);
  CHECK(std::get<HasTurnedParams>(r2.transitions[1].trigger) == HasTurnedParams{45.0, 0.0});
}

TEST_CASE("an explicit initial state, lcm URL, speed and AtGoal goal are used as given") {
  std::string text = replace_once(kRelay, "    hal: tcp://127.0.0.1:8102\n",
                                  "    hal: tcp://127.0.0.1:8102\n    lcm: memq://\n    max_speed_mps: 0.5\n"
                                  "    initial: drive2\n");
  text = replace_once(text, "{from: wait, to: drive2, trigger: Notified, params: {message: r1_done}}",
                      "{from: wait, to: drive2, trigger: Notified, params: {message: r1_done}}\n"
                      "      - {from: finished, to: wait, trigger: AtGoal, params: {goal: [-1, 2e1], radius_m: 1}}");
  text = replace_once(text, "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
                      "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}\n"
                      "      - {from: drive2, to: sink, trigger: HasTurned, params: {angle_deg: 720}}");
  text = replace_once(text, "      - {name: finished, behavior: Stop}\n",
                      "      - {name: finished, behavior: Stop}\n      - {name: sink, behavior: Stop}\n");
  const Mission m = parse_mission(text, "t.yaml");
  const RobotSpec& r2 = m.robots[1];
  CHECK(r2.lcm_url == "memq://");
  CHECK(r2.max_speed_mps == 0.5);
  CHECK(r2.initial == 1);
  CHECK(r2.initial_state().name == "drive2");
  CHECK(std::get<AtGoalParams>(r2.transitions[1].trigger).goal == Point2{-1.0, 20.0});
  CHECK_FALSE(r2.is_final(2));  // finished now loops back to wait
  CHECK(r2.is_final(3));
}

TEST_CASE("a two-robot Bounding Overwatch mission loads as the paper describes it") {
  const Mission m = parse_mission(kBoundingOverwatch, "bo.yaml");
  CHECK(m.name == "bounding_overwatch");
  CHECK(m.criteria == Criteria{200.0, 2.0, 0.8, 0.5, AbortAction::stop_and_notify});
  REQUIRE(m.robots.size() == 2);
  const RobotSpec& r1 = m.robots[0];
  const RobotSpec& r2 = m.robots[1];
  CHECK(r1.start == Pose2{5.5, 5.0, 0.0});
  CHECK(r2.start == Pose2{6.5, 5.0, 0.0});
  CHECK(r1.states.size() == 9);
  CHECK(r2.states.size() == 10);
  CHECK(r1.initial_state().name == "wait_a");
  CHECK(r2.initial_state().name == "go_a");

  // Each robot's implied goal, for the Rmax criterion, is the paper's.
  CHECK(r1.goal == Point2{19.75, 18.0});
  CHECK(r2.goal == Point2{20.0, 17.5});
  CHECK(std::get<GoToGuardedParams>(r1.states[*r1.find_state("go_goal")].behavior).goal == Point2{19.75, 18.0});
  CHECK(std::get<GoToGuardedParams>(r2.states[*r2.find_state("go_goal")].behavior).goal == Point2{20.0, 17.5});

  // Each robot's FSA is a chain ending in its one final state, `done`.
  for (const RobotSpec* r : {&r1, &r2}) {
    for (std::size_t s = 0; s < r->states.size(); ++s) {
      CHECK(r->is_final(s) == (r->states[s].name == "done"));
      if (!r->is_final(s)) CHECK(r->states[s].outgoing.size() == 1);
    }
    // Every AtGoal took its goal from its source state.
    for (const Transition& t : r->transitions) {
      if (const auto* a = std::get_if<AtGoalParams>(&t.trigger)) {
        CHECK(a->goal == std::get<GoToGuardedParams>(r->states[t.from].behavior).goal);
      }
    }
  }
  const auto& turn = r2.transitions[4];
  CHECK(r2.states[turn.from].name == "turn");
  CHECK(std::get<SpinParams>(r2.states[turn.from].behavior).rate_deg_s == 30.0);
  CHECK(std::get<HasTurnedParams>(turn.trigger) == HasTurnedParams{90.0, 5.0});

  // Messages alternate between the robots.
  REQUIRE(m.messages.size() == 4);
  CHECK(m.messages[0].from == 1);
  CHECK(m.messages[0].to == std::vector<std::size_t>{0});
  CHECK(m.messages[3].name == "r1_at_goal");
  CHECK(m.messages[3].from == 0);
  CHECK(std::get<MessageSentParams>(r1.transitions[7].trigger).message == "r1_at_goal");
}

TEST_CASE("a single robot with one Stop state and no transitions is a valid, finished FSA") {
  const Mission m = parse_mission(R"(mission: {name: solo}
criteria: {tmax_s: 1, rmax_m: 1, threshold: 1}
robots:
  - name: r
    start: {x_m: 0, y_m: 0}
    hal: memq://
    states: [{name: idle, behavior: Stop}]
)", "solo.yaml");
  REQUIRE(m.robots.size() == 1);
  CHECK(m.robots[0].goal == Point2{0.0, 0.0});  // it never drives: its goal is where it starts
  CHECK(m.robots[0].is_final(0));
  CHECK(m.robots[0].transitions.empty());
  CHECK(m.messages.empty());
}

TEST_CASE("behavior, trigger and abort-action names map both ways") {
  for (BehaviorKind k : {BehaviorKind::go_to_guarded, BehaviorKind::spin, BehaviorKind::stop, BehaviorKind::notify}) {
    CHECK(behavior_kind_from_string(to_string(k)) == k);
  }
  for (TriggerKind k : {TriggerKind::at_goal, TriggerKind::has_turned, TriggerKind::notified,
                        TriggerKind::message_sent}) {
    CHECK(trigger_kind_from_string(to_string(k)) == k);
  }
  CHECK(to_string(BehaviorKind::go_to_guarded) == "GoToGuarded");
  CHECK(to_string(TriggerKind::message_sent) == "MessageSent");
  CHECK_FALSE(behavior_kind_from_string("gotoguarded").has_value());
  CHECK_FALSE(trigger_kind_from_string("").has_value());
  CHECK(abort_action_from_string("stop_and_notify") == AbortAction::stop_and_notify);
  CHECK_FALSE(abort_action_from_string("abort").has_value());
  CHECK(kind_of(BehaviorParams{SpinParams{10.0}}) == BehaviorKind::spin);
  CHECK(kind_of(TriggerParams{NotifiedParams{"m"}}) == TriggerKind::notified);
}

TEST_CASE("load_mission_file reads the example relay mission") {
  const Mission m = load_mission_file(std::string(P3AT_EXAMPLES_DIR) + "/relay/mission.yaml");
  CHECK(m.name == "relay");
  REQUIRE(m.robots.size() == 2);
  CHECK(m.robots[0].states.size() == 3);
  CHECK(m.robots[1].initial_state().name == "wait");
  CHECK(m.description == "robot1 drives 2 m, notifies robot2, then robot2 drives 2 m");
}

TEST_CASE("load_mission_file reports the path with line and column") {
  const std::string path = std::string(P3AT_MISSION_TEST_DATA) + "/bad_behavior.yaml";
  try {
    (void)load_mission_file(path);
    FAIL("loaded a bad mission");
  } catch (const MissionError& e) {
    CHECK(e.file() == path);
    CHECK(e.line() == 6);
    CHECK(e.column() == 28);
    CHECK(e.detail() == "unknown behavior 'GoToGaurded' (expected one of GoToGuarded, Spin, Stop, Notify)");
    CHECK(std::string(e.what()) == path + ":6:28: " + e.detail());
  }
}

TEST_CASE("load_mission_file refuses a file too large to be a mission") {
  const std::filesystem::path path = p3at::test::scratch_path("too_large.yaml");
  {
    std::ofstream out(path, std::ios::binary);
    const std::string chunk(1024 * 1024, ' ');
    for (int i = 0; i < 17; ++i) out << chunk;
  }
  try {
    (void)load_mission_file(path.string());
    FAIL("loaded a 17 MiB file");
  } catch (const MissionError& e) {
    CHECK(std::string(e.what()) == path.string() + ": mission file too large (17825792 bytes, limit 16777216)");
  }
  std::filesystem::remove(path);
}

TEST_CASE("load_mission_file on a missing file or a directory throws without a position") {
  const std::string missing = std::string(P3AT_MISSION_TEST_DATA) + "/no_such_mission.yaml";
  try {
    (void)load_mission_file(missing);
    FAIL("loaded a missing file");
  } catch (const MissionError& e) {
    CHECK(e.line() == 0);
    CHECK(e.column() == 0);
    CHECK(std::string(e.what()) == missing + ": cannot open mission file: No such file or directory");
  }
  try {
    (void)load_mission_file(P3AT_MISSION_TEST_DATA);
    FAIL("loaded a directory");
  } catch (const MissionError& e) {
    CHECK(std::string(e.what()) == std::string(P3AT_MISSION_TEST_DATA) + ": cannot open mission file: it is a directory");
  }
}
