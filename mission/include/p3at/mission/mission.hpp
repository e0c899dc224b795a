#pragma once
/// The mission model: one finite state automaton (FSA) per robot, the team's
/// messages, and the performance criteria the verifier checks.
///
/// Plain value types, fully resolved: every default is filled in by the loader
/// (loader.hpp), states and robots are referred to by index, and a loaded
/// Mission is valid (every check of docs/mission-format.md holds). The
/// executive and the verifier both read it; neither depends on the other.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace p3at::mission {

/// LCM URL a robot uses when the mission file gives none.
inline constexpr std::string_view kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";
/// Robot speed cap when the mission file gives none (the seed paper's P3-ATs).
inline constexpr double kDefaultMaxSpeedMps = 0.3;

/// A point in the world frame, metres.
struct Point2 {
  double x_m = 0.0;
  double y_m = 0.0;
  bool operator==(const Point2&) const = default;
};

/// A pose in the world frame: metres, and heading in degrees counter-clockwise from +X.
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_deg = 0.0;
  bool operator==(const Pose2&) const = default;
};

// ---------------------------------------------------------------- behaviors

/// GoToGuarded = COOP(MOVE_TO_GUARDED, AVOID_OBSTACLES, NOISE) (docs/mission-format.md).
struct GoToGuardedParams {
  Point2 goal;                           ///< required; world frame
  double dropoff_m = 2.5;                ///< move gain ramps down inside this radius
  double dead_zone_m = 0.05;             ///< move output is zero inside this radius
  double move_gain = 1.0;                ///< COOP weight of MOVE_TO_GUARDED
  double avoid_gain = 1.0;               ///< COOP weight of AVOID_OBSTACLES
  double noise_gain = 0.1;               ///< COOP weight of NOISE
  double sphere_m = 1.0;                 ///< obstacle influence beyond the safety margin
  double safety_margin_m = 0.25;         ///< distance treated as contact
  std::int64_t noise_persistence_cycles = 10;  ///< control cycles a noise direction is held
  bool operator==(const GoToGuardedParams&) const = default;
};

/// Rotate in place at a fixed rate.
struct SpinParams {
  double rate_deg_s = 0.0;  ///< required, non-zero; + = counter-clockwise
  bool operator==(const SpinParams&) const = default;
};

/// Zero motion.
struct StopParams {
  bool operator==(const StopParams&) const = default;
};

/// On entering the state, send `message` to its recipients; zero motion.
struct NotifyParams {
  std::string message;  ///< a name from Mission::messages whose sender is this robot
  bool operator==(const NotifyParams&) const = default;
};

enum class BehaviorKind { go_to_guarded, spin, stop, notify };

/// A behavior and its parameters; the alternative's index is its BehaviorKind.
using BehaviorParams = std::variant<GoToGuardedParams, SpinParams, StopParams, NotifyParams>;

/// The mission-file spelling of a behavior: "GoToGuarded", "Spin", "Stop", "Notify".
std::string_view to_string(BehaviorKind kind);
/// Inverse of to_string(BehaviorKind); nullopt for anything else (case-sensitive).
std::optional<BehaviorKind> behavior_kind_from_string(std::string_view name);
BehaviorKind kind_of(const BehaviorParams& params);

// ----------------------------------------------------------------- triggers

/// True when the goal, as the robot believes from its odometry, is within radius_m.
struct AtGoalParams {
  Point2 goal;            ///< resolved: the source state's GoToGuarded goal unless given
  double radius_m = 0.0;  ///< required, > 0
  bool operator==(const AtGoalParams&) const = default;
};

/// True once the absolute heading change accumulated since entering the source
/// state reaches angle_deg - offset_deg.
struct HasTurnedParams {
  double angle_deg = 0.0;   ///< required, > 0
  double offset_deg = 0.0;  ///< 0 <= offset_deg < angle_deg
  bool operator==(const HasTurnedParams&) const = default;
};

/// True once `message` has been received from a teammate.
struct NotifiedParams {
  std::string message;
  bool operator==(const NotifiedParams&) const = default;
};

/// True once this robot's own `message` has gone out (and been acknowledged).
struct MessageSentParams {
  std::string message;  ///< resolved: the source state's Notify message unless given
  bool operator==(const MessageSentParams&) const = default;
};

enum class TriggerKind { at_goal, has_turned, notified, message_sent };

/// A trigger and its parameters; the alternative's index is its TriggerKind.
using TriggerParams = std::variant<AtGoalParams, HasTurnedParams, NotifiedParams, MessageSentParams>;

/// The mission-file spelling of a trigger: "AtGoal", "HasTurned", "Notified", "MessageSent".
std::string_view to_string(TriggerKind kind);
/// Inverse of to_string(TriggerKind); nullopt for anything else (case-sensitive).
std::optional<TriggerKind> trigger_kind_from_string(std::string_view name);
TriggerKind kind_of(const TriggerParams& params);

// ---------------------------------------------------------------- the model

/// One FSA state: a named behavior with its parameters.
struct State {
  std::string name;
  BehaviorParams behavior;
  /// Indices into RobotSpec::transitions of the transitions leaving this state,
  /// in file order (the order in which they are checked each cycle; the first
  /// whose trigger holds fires). Empty for a final state.
  std::vector<std::size_t> outgoing;

  BehaviorKind kind() const { return kind_of(behavior); }
  bool operator==(const State&) const = default;
};

/// One FSA transition, by state index.
struct Transition {
  std::size_t from = 0;  ///< index into RobotSpec::states
  std::size_t to = 0;    ///< index into RobotSpec::states
  TriggerParams trigger;

  TriggerKind kind() const { return kind_of(trigger); }
  bool operator==(const Transition&) const = default;
};

/// One robot of the team and its FSA.
struct RobotSpec {
  std::string name;
  Pose2 start;                                   ///< true starting pose, world frame
  /// Where the robot must end, within Criteria::rmax_m (true position). Resolved:
  /// as given; else the goal of the GoToGuarded states met first walking back
  /// from every final state (the loader rejects them disagreeing); else start's x, y.
  Point2 goal;
  std::string hal_url;                           ///< default HAL URL (a command line may override)
  std::string lcm_url{kDefaultLcmUrl};           ///< team link URL
  double max_speed_mps = kDefaultMaxSpeedMps;    ///< translational speed cap
  std::size_t initial = 0;                       ///< index into states
  std::vector<State> states;                     ///< never empty in a loaded mission
  std::vector<Transition> transitions;

  /// The state the FSA starts in. Precondition: states is not empty (true of a loaded mission).
  const State& initial_state() const { return states.at(initial); }
  /// True if the state has no outgoing transition: the FSA is finished when it
  /// reaches one. False for an index out of range.
  bool is_final(std::size_t state_index) const {
    return state_index < states.size() && states[state_index].outgoing.empty();
  }
  /// Index of the state with that name, if any.
  std::optional<std::size_t> find_state(std::string_view state_name) const;
  bool operator==(const RobotSpec&) const = default;
};

/// What happens when in-mission re-verification falls below Criteria::abort_threshold.
enum class AbortAction { continue_and_warn, stop_and_notify };
std::string_view to_string(AbortAction action);
std::optional<AbortAction> abort_action_from_string(std::string_view name);

/// Success = every robot ends within rmax_m of its goal (true position) and the
/// mission is done by tmax_s; launch requires P(success) >= threshold.
struct Criteria {
  double tmax_s = 0.0;          ///< > 0
  double rmax_m = 0.0;          ///< > 0
  double threshold = 0.0;       ///< minimum acceptable P(success), in (0, 1]
  double abort_threshold = 0.0; ///< in-mission re-verification floor, in [0, threshold]; 0 = off
  AbortAction abort_action = AbortAction::continue_and_warn;
  bool operator==(const Criteria&) const = default;
};

/// A team message: who sends it (with a Notify state) and who listens.
struct Message {
  std::string name;
  std::size_t from = 0;          ///< index into Mission::robots
  std::vector<std::size_t> to;   ///< indices into Mission::robots; non-empty, sender excluded
  bool operator==(const Message&) const = default;
};

struct Mission {
  std::string name;
  std::string description;
  Criteria criteria;
  std::vector<RobotSpec> robots;
  std::vector<Message> messages;

  std::optional<std::size_t> find_robot(std::string_view robot_name) const;
  std::optional<std::size_t> find_message(std::string_view message_name) const;
  bool operator==(const Mission&) const = default;
};

}  // namespace p3at::mission
