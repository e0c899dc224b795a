#pragma once
/// Calibration: the robot-models file (models.hpp) fitted from data, never
/// from a simulator's own parameters (docs/calibration.md).
///
/// The data is a log of calibration manoeuvres (straight runs and spins,
/// one row per control cycle: the command, the odometry and, where known,
/// the true pose) and of team-link notifications (sent, delivered and
/// acknowledged times), in a documented CSV format that `vipars calibrate`
/// writes when it drives the manoeuvres itself and that a lab can write from
/// its own runs (a tape measure at each manoeuvre's start and end is enough).
///
/// Nothing here depends on the simulator or the HAL: the library fits what
/// a lab could measure, whoever drove the robots.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/located_error.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {

enum class ManoeuvreKind {
  straight,  ///< constant translational command, no rotation
  spin,      ///< constant rotational command, no translation
};
/// "straight", "spin" (the log's spelling).
const char* to_string(ManoeuvreKind kind);

/// A ground-truth pose in any fixed frame (a motion-capture frame, the floor's
/// tape marks): only differences between a manoeuvre's two ends are used.
struct TruePose {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
  bool operator==(const TruePose&) const = default;
};

/// One control cycle of a manoeuvre: the robot's report, and the command sent
/// right after it (in force until the next row).
struct CycleRow {
  double t_s = 0.0;
  double cmd_trans_mps = 0.0;
  double cmd_rot_radps = 0.0;
  double odom_x_m = 0.0;      ///< odometry, the robot's own frame
  double odom_y_m = 0.0;
  double odom_theta_rad = 0.0;
  std::optional<TruePose> truth;
  int line = 0;               ///< line in the log it came from (0: not from a file)
  bool operator==(const CycleRow&) const = default;
};

/// One manoeuvre of one robot: consecutive cycles, from rest to rest.
struct Manoeuvre {
  std::string robot;
  std::int64_t id = 0;        ///< unique per robot
  ManoeuvreKind kind = ManoeuvreKind::straight;
  std::vector<CycleRow> rows;
  bool operator==(const Manoeuvre&) const = default;
};

/// One notification across the team link. Times in seconds on the sender's
/// clock (or one clock shared by both robots); an absent time means the
/// message was never delivered / acknowledged.
struct MessageRow {
  std::string sender;
  std::int64_t id = 0;
  double sent_s = 0.0;
  std::optional<double> delivered_s;
  std::optional<double> acked_s;
  int line = 0;
  bool operator==(const MessageRow&) const = default;
};

struct CalibrationLog {
  std::vector<Manoeuvre> manoeuvres;  ///< in order of first appearance
  std::vector<MessageRow> messages;   ///< in file order
  bool operator==(const CalibrationLog&) const = default;
};

/// A log that cannot be read: "file:line:column: detail".
class CalibrationLogError : public LocatedError {
 public:
  using LocatedError::LocatedError;
};

/// The log's column names, in the order write_calibration_log() uses (the
/// reader accepts any order, every column present exactly once).
const std::vector<std::string>& calibration_log_columns();
/// Parses a log (docs/calibration.md). Throws CalibrationLogError at the first problem.
CalibrationLog parse_calibration_log(std::string_view text, const std::string& source_name);
/// Reads and parses the file at `path`.
CalibrationLog load_calibration_log(const std::string& path);
/// The log as CSV (header, then rows; numbers round-trip exactly).
std::string write_calibration_log(const CalibrationLog& log);

/// How well one parameter is known. Values are in the models file's units
/// (`unit`), so the report reads like the file.
struct ParameterFit {
  std::string name;                 ///< the models-file key, e.g. "trans_scale"
  double value = 0.0;
  double std_error = -1.0;          ///< standard error; < 0 when not available
  double residual_rms = -1.0;       ///< RMS of the fit's residuals (in `residual_unit`); < 0 when none
  std::string unit;
  std::string residual_unit;
  std::size_t runs = 0;             ///< manoeuvres (or ramps, or messages) it was fitted from; 0 = default kept
  std::string note;
};

struct RobotCalibration {
  RobotModel model;
  std::size_t straights = 0;        ///< straight runs with true poses at both ends
  std::size_t spins = 0;            ///< spins with true poses at both ends
  std::vector<ParameterFit> fits;
};

/// A delay distribution fitted by EM, with the number of components chosen by BIC.
struct DelayCalibration {
  Mixture1 mixture;                 ///< empty when there was no sample
  std::size_t samples = 0;
  std::size_t lost = 0;             ///< messages never delivered / acknowledged (not in the mixture)
  std::vector<double> bic;          ///< BIC for 1, 2, ... components (lower is better)
  double ks_distance = 0.0;         ///< max |empirical CDF - mixture CDF|
};

struct CalibrationOptions {
  std::size_t max_delay_components = 3;  ///< BIC chooses among 1..this
  /// Kept for what the data cannot give (the executive's robot_radius_m and
  /// rot_gain; anything with too few ramps).
  Kinematics kinematics_defaults;
};

struct CalibrationResult {
  std::vector<RobotCalibration> robots;  ///< in order of first appearance in the log
  DelayCalibration delivery;
  DelayCalibration ack;
  std::vector<std::string> warnings;     ///< data left unused, defaults kept, ...
};

/// Data that cannot give a model (too few manoeuvres with true poses, a
/// manoeuvre that did not move); what() names the robot and what is missing.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Fits every robot's kinematics and motion error, and the two delays. Each
/// robot needs at least 2 straight runs and 2 spins with true poses at both
/// ends (more give tighter fits; the report says how tight).
CalibrationResult calibrate(const CalibrationLog& log, const CalibrationOptions& options = {});

/// The fit quality, one line per parameter, for people.
std::string format_calibration_report(const CalibrationResult& result);

/// The fitted robots and link as a models file's content (environment and
/// budget at their defaults; the caller adds walls and generated_by).
Models to_models(const CalibrationResult& result);

/// Fits a mixture of 1..max_components Gaussians by EM (fit_em) and keeps the
/// one with the lowest BIC. Exposed for tests.
DelayCalibration fit_delay(const std::vector<double>& samples_s, std::size_t lost, std::size_t max_components);

}  // namespace p3at::verifier
