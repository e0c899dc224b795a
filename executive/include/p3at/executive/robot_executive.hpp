#pragma once
/// One robot's mission executive: runs its FSA from the mission model, one
/// non-blocking cycle() per controller update (docs/executive.md).
///
/// Calling contract (the same in real time and in fast time):
///  - One thread calls everything. Before each cycle(), the caller lets the
///    DriveBase take in its latest controller update (real time:
///    DriveBase::wait_for_update(), see realtime_loop.hpp; fast time: the
///    simulator steps its world so DriveBase::state() holds the new cycle, e.g.
///    sim::SimDriveBase::wait_for_update()) and the Clock reads that cycle's time.
///  - cycle() never blocks and never sleeps: it reads DriveBase::state() and
///    Clock::now_us(), calls TeamLink::poll() / notify() / publish_*() and sends
///    exactly one motion request (DriveBase::set_velocity(), or stop() when the
///    mission ends), and returns. It never calls wait_for_update().
///  - Call cycle() once per 100 ms controller cycle. The first call starts the
///    mission: the odometry then is taken as the mission's origin (the robot is
///    at its RobotSpec::start pose) and the initial state is entered.
///  - Keep calling cycle() after the outcome is finished or aborted for as long as
///    teammates may still need this robot's acknowledgements (until
///    team_settled(), or a timeout): it then only polls the team link and
///    republishes its status, and commands no motion.
///  - cycle() throws nothing; construction throws std::invalid_argument for a
///    robot index or mission structure it cannot run (configuration errors).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "p3at/executive/behaviors.hpp"
#include "p3at/executive/cycle_stats.hpp"
#include "p3at/executive/noise.hpp"
#include "p3at/executive/schemas.hpp"
#include "p3at/executive/triggers.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::exec {

/// Where the mission stands for this robot.
enum class Phase {
  running,   ///< started or about to start: the FSA is not in a final state
  finished,  ///< the FSA reached a final state (a state with no outgoing transition)
  aborted,   ///< stopped early: link loss, safety stop, refused motion, teammate abort, interrupt
};

/// "running", "finished", "aborted" (also the TeamStatus phase strings).
const char* to_string(Phase phase);

struct Outcome {
  Phase phase = Phase::running;
  std::string reason;  ///< why aborted (empty otherwise)
};

/// One FSA transition as it happened, for whoever records runs (calibration,
/// fast-time trials) without parsing logs.
struct TransitionEvent {
  std::size_t robot = 0;            ///< index into Mission::robots
  double t_s = 0.0;                 ///< since mission start
  std::size_t from = 0;             ///< state indices into RobotSpec::states
  std::size_t to = 0;
  mission::TriggerKind cause = mission::TriggerKind::at_goal;
  Pose<double> pose;                ///< mission frame, from odometry
};

struct ExecutiveOptions {
  std::uint64_t seed = 0;                   ///< run seed for the NOISE schema
  std::int64_t period_us = 100'000;         ///< cycle period: compute time above it is an overrun
  std::uint32_t telemetry_every_cycles = 1; ///< publish telemetry every N cycles; 0 = never
  std::uint32_t status_every_cycles = 10;   ///< status heartbeat every N cycles (besides every change); 0 = only changes
  double max_rot_radps = 0.75;              ///< rotational cap for GoToGuarded and Spin
  double rot_gain = 1.5;                    ///< rad/s per rad of heading error
  double robot_radius_m = 0.4;              ///< AVOID_OBSTACLES' robot radius (see BehaviorConfig)
  double sonar_max_range_m = 5.0;           ///< sonar readings at/over this are "nothing seen"
  double p_success = -1.0;                  ///< verified probability to report in status; < 0 = unknown
  std::function<void(const TransitionEvent&)> on_transition;  ///< optional; called inside cycle()
};

class RobotExecutive {
 public:
  /// Runs `mission.robots[robot_index]`. Copies the mission; keeps references to
  /// `drive`, `team_link` and `clock`, which must outlive this object.
  /// Throws std::invalid_argument (naming the problem) for an index out of range or
  /// a mission whose indices or message names do not resolve.
  RobotExecutive(const mission::Mission& mission, std::size_t robot_index, hal::DriveBase& drive,
                 hal::TeamLink& team_link, hal::Clock& clock, ExecutiveOptions options = {});
  RobotExecutive(const RobotExecutive&) = delete;
  RobotExecutive& operator=(const RobotExecutive&) = delete;

  /// One control cycle: read drive state → poll team link → safety checks →
  /// evaluate the current state's transitions in file order (at most one fires)
  /// → behavior output → one velocity command. Telemetry and status as configured.
  void cycle();

  /// Aborts now (e.g. on SIGINT): stops the robot, logs and publishes the reason.
  /// No effect once finished or aborted.
  void abort(const std::string& reason);

  /// Publishes this robot's status now (phase, state, reason).
  void publish_status();

  const Outcome& outcome() const { return outcome_; }
  bool running() const { return outcome_.phase == Phase::running; }
  /// True after the first cycle().
  bool started() const { return started_; }
  /// True when every teammate has reported "finished" or "aborted".
  bool team_settled() const;

  std::size_t state_index() const { return current_; }
  const std::string& state_name() const;
  /// Pose in the mission frame from odometry (the robot's belief), heading continuous.
  const Pose<double>& pose() const { return pose_; }
  /// Σ|Δheading| since the current state was entered, radians.
  double turned_rad() const { return turned_rad_; }
  /// Seconds since the first cycle(); frozen when the mission finishes or aborts.
  double elapsed_s() const;
  /// The velocity command sent in the latest cycle.
  const Velocity<double>& last_command() const { return last_command_; }
  std::uint64_t transition_count() const { return transition_count_; }

  const CycleStats& stats() const { return stats_; }
  /// Records a stall seen by the driver (run_realtime): cycles not run.
  void note_stall(std::uint64_t missed_cycles, std::int64_t stall_ms) { stats_.record_stall(missed_cycles, stall_ms); }
  const MessageBook& messages() const { return messages_; }
  const NoiseSource& noise() const { return noise_; }
  const mission::Mission& mission() const { return mission_; }
  const mission::RobotSpec& robot() const { return mission_.robots[robot_index_]; }
  std::size_t robot_index() const { return robot_index_; }
  hal::Clock& clock() const { return clock_; }
  const ExecutiveOptions& options() const { return options_; }

 private:
  void validate() const;
  void start(std::int64_t now_us, const hal::DriveState& state);
  void update_pose(const hal::DriveState& state);
  void poll_team(std::int64_t now_us);
  bool check_safety(const hal::DriveState& state);
  void evaluate_transitions();
  void enter_state(std::size_t index);
  void send_notification(const mission::NotifyParams& params);
  void command_motion(const hal::DriveState& state);
  void finish();
  void abort_now(const std::string& reason);
  void publish_telemetry(const hal::DriveState& state);
  std::string pose_fields() const;

  mission::Mission mission_;
  std::size_t robot_index_;
  hal::DriveBase& drive_;
  hal::TeamLink& team_link_;
  hal::Clock& clock_;
  ExecutiveOptions options_;
  BehaviorConfig behavior_config_;
  /// Per transition of this robot: the Mission::messages index of its trigger's message.
  std::vector<std::optional<std::size_t>> transition_message_;
  /// Per state of this robot: the Mission::messages index of its Notify message.
  std::vector<std::optional<std::size_t>> state_message_;

  Outcome outcome_;
  bool started_ = false;
  bool entered_initial_ = false;
  std::size_t current_ = 0;
  std::int64_t start_us_ = 0;
  std::int64_t now_us_ = 0;
  std::optional<std::int64_t> end_us_;
  hal::Pose2 odometry_origin_;
  Pose<double> pose_;
  double turned_rad_ = 0.0;
  std::uint64_t last_update_count_ = 0;
  std::uint64_t cycle_count_ = 0;
  std::uint64_t transition_count_ = 0;
  std::uint64_t poll_errors_ = 0;
  std::uint64_t publish_errors_ = 0;
  bool status_published_this_cycle_ = false;
  Velocity<double> last_command_;
  MessageBook messages_;
  NoiseSource noise_;
  CycleStats stats_;
  std::vector<hal::TeamNotification> inbox_;  ///< reused every cycle
};

}  // namespace p3at::exec
