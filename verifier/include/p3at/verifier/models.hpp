#pragma once
/// What the verifier knows about the robots, the radio and the environment:
/// the robot-models file (docs/robot-models.md). The verifier never reads the
/// simulator's error parameters; it knows each robot only through this file,
/// which `vipars calibrate` writes from data (or an engineer writes by hand).
///
/// Plain value types; load_models() fills every default and validates ranges.

#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/located_error.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {

/// How a robot's base answers velocity commands (the firmware's limits). The
/// executive commands once per control cycle; the base ramps toward it.
struct Kinematics {
  double cycle_s = 0.1;              ///< control (SIP) period
  double max_rot_vel_radps = 0.75;   ///< rotational cap, the executive's and the firmware's
  double trans_accel_mps2 = 0.3;     ///< ramp up
  double trans_decel_mps2 = 0.3;     ///< ramp down
  double rot_accel_radps2 = 100.0 * std::numbers::pi / 180.0;  ///< 100 deg/s^2, the firmware's default
  double rot_decel_radps2 = 100.0 * std::numbers::pi / 180.0;
  double robot_radius_m = 0.4;       ///< AVOID_OBSTACLES' robot radius (executive default)
  double rot_gain = 1.5;             ///< vector_to_velocity's gain (executive default)
  /// The translational speed the motion model was calibrated at (`vipars
  /// calibrate --speed`); 0 = unknown (a file from before it was recorded):
  /// a mission faster than this is outside what the model was fitted on.
  double calibrated_speed_mps = 0.0;
  /// The base's physical top speed: a mission's max_speed_mps above it is
  /// never reached. Default the P3-AT's (0.6 m/s, the simulator's and MobileSim's cap).
  double top_speed_mps = 0.6;
  bool operator==(const Kinematics&) const = default;
};

/// z(u, t) of the paper's Robot_{r,q} template: how the true motion differs
/// from the odometric motion the executive steers by, per control cycle with
/// odometric increments (ds metres along the heading, dth radians):
///   true ds  = trans_scale * ds + e_s,   var(e_s)  = trans_var_per_m * |ds|
///   true ds  also gains trans_per_rad_m * dth (a turn's own forward motion),
///   true dth = rot_scale * dth + drift_rad_per_m * ds + e_th,
///              var(e_th) = rot_var_per_rad * |dth| + heading_var_per_m * |ds|
///                          + rot_rel_var * dth^2
/// and var(e_s) has a further trans_rel_var * ds^2: the per-unit terms model an
/// error that grows with distance or angle whatever the speed; the relative
/// (per-cycle) terms an encoder error proportional to each cycle's increment,
/// so slow, gradual turns add less than a fast spin through the same angle.
/// Scales carry the systematic error (wheel diameter, effective track), the
/// variances the random part; both fitted by calibration.
struct MotionError {
  double trans_scale = 1.0;
  double rot_scale = 1.0;
  double drift_rad_per_m = 0.0;
  /// Metres the robot really moves along its heading per radian the odometry
  /// turns (signed: left turns forward when positive). Wheels whose scales
  /// differ do not cancel in a turn: a P3-AT whose right wheel reads 6 %
  /// less than its left moves about 9 mm per radian of spin, 1.7 cm over a
  /// 107-degree turn, which the odometry never sees.
  double trans_per_rad_m = 0.0;
  double trans_var_per_m = 0.0;     ///< m^2 per metre travelled
  double rot_var_per_rad = 0.0;     ///< rad^2 per radian turned
  double heading_var_per_m = 0.0;   ///< rad^2 per metre travelled
  double trans_rel_var = 0.0;       ///< variance of each cycle's relative distance error
  double rot_rel_var = 0.0;         ///< variance of each cycle's relative rotation error
  bool operator==(const MotionError&) const = default;
};

struct RobotModel {
  std::string name;                 ///< matches a mission robot's name
  Kinematics kinematics;
  MotionError motion;
  bool operator==(const RobotModel&) const = default;
};

/// The team link as the mission sees it (docs/robot-models.md):
///   delivery_s: from a Notify state's send to the recipient holding the message
///               (retransmissions included);
///   ack_s:      from the send to the sender holding the acknowledgement (what
///               MessageSent waits for).
/// Both default to a point mass at 0 (an ideal link), as when the file has
/// no `communication:` block.
struct CommModel {
  Mixture1 delivery_s = Mixture1::point(0.0);
  Mixture1 ack_s = Mixture1::point(0.0);
  bool operator==(const CommModel&) const = default;
};

/// A wall segment, world frame, metres.
struct Wall {
  double x0_m = 0.0, y0_m = 0.0, x1_m = 0.0, y1_m = 0.0;
  bool operator==(const Wall&) const = default;
};

/// The sensor and environment model: the map the sonar sees.
struct Environment {
  std::vector<Wall> walls;
  double sonar_max_range_m = 5.0;
  bool operator==(const Environment&) const = default;
};

/// Bounds that keep the verifier's work fixed (docs/verifier.md).
struct Budget {
  std::size_t max_components = 8;       ///< per random variable after merge/prune
  std::size_t max_branches = 32;        ///< orderings carried at once
  std::size_t noise_sigma_points = 8;   ///< directions for NOISE's uniform angle
  std::size_t max_events = 10000;       ///< FSA transitions per robot before giving up (loops)
  /// Robot control cycles the within-state models may simulate over the whole
  /// mission (StateAnalysis::cycles_simulated, summed): the verifier's time
  /// bound on a robot before launch. Branches still unevaluated when it runs
  /// out are counted as failure (a lower bound on success, never a GO it
  /// cannot vouch for) and said (SystemOutcome::work_cutoff_mass).
  std::size_t max_work_cycles = 100'000'000;
  bool operator==(const Budget&) const = default;
};

struct Models {
  std::string source;               ///< the file it came from (for messages and reports)
  std::string generated_by;         ///< `models.generated_by`: free text (calibrate's command line), may be empty
  std::vector<RobotModel> robots;
  CommModel comm;
  Environment environment;
  Budget budget;

  /// The model for the named robot, or nullptr.
  const RobotModel* find_robot(std::string_view name) const;
  bool operator==(const Models&) const = default;
};

/// A models file that cannot be loaded: "file:line:column: detail".
class ModelsError : public LocatedError {
 public:
  using LocatedError::LocatedError;
};

/// Parses a models file (YAML). A relative `environment.walls_from` path is
/// resolved against `base_dir`. Throws ModelsError for the first problem.
Models parse_models(std::string_view yaml_text, const std::string& source_name, const std::string& base_dir);
/// Reads and parses the file at `path` (walls_from relative to its folder).
Models load_models_file(const std::string& path);
/// The models file for `models`, in the documented format, loadable again
/// with the same values (calibration writes it; parse(write(m)) == m up to
/// the printed precision).
std::string write_models(const Models& models);

}  // namespace p3at::verifier
