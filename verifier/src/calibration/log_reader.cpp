// parse_calibration_log(): the calibration log's CSV (docs/calibration.md)
// into manoeuvres and messages. Every field is checked where it stands, so an
// error names the line and the column of the offending field; a lab's
// hand-edited log (true poses typed in from a tape measure) is exactly the
// kind of file that needs that.

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "p3at/mission/names.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::verifier {
namespace {

// Far more than any calibration campaign writes; keeps a wrong path (a disk
// image, a video) from being read whole.
constexpr std::size_t kMaxLogBytes = 512U * 1024U * 1024U;

enum Column : std::size_t {
  kRobot, kId, kKind, kT, kCmdTrans, kCmdRot, kOdomX, kOdomY, kOdomTheta,
  kTrueX, kTrueY, kTrueTheta, kSent, kDelivered, kAcked, kColumnCount
};

// User text made safe to quote in a one-line message.
std::string show(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c >= 0x7f) {
      constexpr std::string_view kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4U];
      out += kHex[c & 0xFU];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out;
}

// One field of a line: its text (trimmed) and the 1-based column it starts at.
struct Field {
  std::string_view text;
  int column = 1;
};

std::vector<Field> split_fields(std::string_view line) {
  std::vector<Field> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? line.size() : comma;
    std::size_t a = start;
    std::size_t b = end;
    while (a < b && (line[a] == ' ' || line[a] == '\t')) ++a;
    while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t')) --b;
    fields.push_back(Field{line.substr(a, b - a), static_cast<int>(a) + 1});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(int line, int column, std::string detail) const {
    throw CalibrationLogError(source_, line, column, std::move(detail));
  }

  CalibrationLog read(std::string_view text) {
    std::size_t pos = 0;
    int line_no = 0;
    bool have_header = false;
    while (pos <= text.size()) {
      const std::size_t nl = text.find('\n', pos);
      std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
      pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      const std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string_view::npos || line[first] == '#') continue;  // blank or comment
      if (line.find('\0') != std::string_view::npos) fail(line_no, 1, "unexpected NUL byte (not a text file?)");
      const std::vector<Field> fields = split_fields(line);
      if (!have_header) {
        read_header(fields, line_no);
        have_header = true;
      } else {
        read_row(fields, line_no, static_cast<int>(line.size()) + 1);
      }
    }
    if (!have_header) fail(line_no, 1, "empty calibration log (expected a header line: " + header_text() + ")");
    return std::move(log_);
  }

 private:
  static std::string header_text() {
    std::string out;
    for (const std::string& c : calibration_log_columns()) out += (out.empty() ? "" : ",") + c;
    return out;
  }

  void read_header(const std::vector<Field>& fields, int line) {
    const std::vector<std::string>& names = calibration_log_columns();
    index_.fill(kColumnCount);
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const auto it = std::find(names.begin(), names.end(), fields[i].text);
      if (it == names.end()) {
        fail(line, fields[i].column, "unknown column '" + show(fields[i].text) + "' in the header (expected the columns " +
                                         header_text() + ", in any order)");
      }
      const auto c = static_cast<std::size_t>(it - names.begin());
      if (index_[c] != kColumnCount) fail(line, fields[i].column, "duplicate column '" + *it + "' in the header");
      index_[c] = i;
    }
    std::string missing;
    for (std::size_t c = 0; c < kColumnCount; ++c) {
      if (index_[c] == kColumnCount) missing += (missing.empty() ? "" : ", ") + names[c];
    }
    if (!missing.empty()) fail(line, 1, "missing column(s) in the header: " + missing);
    width_ = fields.size();
  }

  const Field& field(const std::vector<Field>& fields, Column c) const { return fields[index_[c]]; }

  double number(const Field& f, int line, std::string_view name) const {
    double value = 0.0;
    const char* first = f.text.data();
    const char* last = first + f.text.size();
    if (!f.text.empty() && *first == '+') ++first;  // from_chars takes no '+'; people write it
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (f.text.empty() || ec != std::errc() || ptr != last || !std::isfinite(value)) {
      fail(line, f.column, "expected a finite number for '" + std::string(name) + "', got " +
                               (f.text.empty() ? std::string("an empty field") : "'" + show(f.text) + "'"));
    }
    return value;
  }

  std::optional<double> optional_number(const Field& f, int line, std::string_view name) const {
    if (f.text.empty()) return std::nullopt;
    return number(f, line, name);
  }

  void require_empty(const std::vector<Field>& fields, int line, std::initializer_list<Column> columns,
                     std::string_view why) const {
    for (const Column c : columns) {
      const Field& f = field(fields, c);
      if (!f.text.empty()) {
        fail(line, f.column, "expected an empty '" + calibration_log_columns()[c] + "' " + std::string(why) +
                                 ", got '" + show(f.text) + "'");
      }
    }
  }

  void read_row(const std::vector<Field>& fields, int line, int end_column) {
    if (fields.size() != width_) {
      fail(line, fields.size() > width_ ? fields[width_].column : end_column,
           "expected " + std::to_string(width_) + " fields (as in the header), got " + std::to_string(fields.size()));
    }
    const Field& robot = field(fields, kRobot);
    if (!mission::is_valid_name(robot.text)) {
      fail(line, robot.column, "invalid robot name '" + show(robot.text) +
                                   "' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
    }
    const Field& id_field = field(fields, kId);
    std::int64_t id = 0;
    {
      const auto [ptr, ec] = std::from_chars(id_field.text.data(), id_field.text.data() + id_field.text.size(), id);
      if (id_field.text.empty() || ec != std::errc() || ptr != id_field.text.data() + id_field.text.size() || id < 0) {
        fail(line, id_field.column, "expected a whole number >= 0 for 'id', got " +
                                        (id_field.text.empty() ? std::string("an empty field")
                                                               : "'" + show(id_field.text) + "'"));
      }
    }
    const Field& kind = field(fields, kKind);
    if (kind.text == "message") {
      read_message(fields, line, std::string(robot.text), id);
    } else if (kind.text == "straight" || kind.text == "spin") {
      read_cycle(fields, line, std::string(robot.text), id,
                 kind.text == "straight" ? ManoeuvreKind::straight : ManoeuvreKind::spin);
    } else {
      fail(line, kind.column, "unknown kind '" + show(kind.text) + "' (expected straight, spin or message)");
    }
  }

  void read_message(const std::vector<Field>& fields, int line, std::string sender, std::int64_t id) {
    require_empty(fields, line,
                  {kT, kCmdTrans, kCmdRot, kOdomX, kOdomY, kOdomTheta, kTrueX, kTrueY, kTrueTheta},
                  "on a message row");
    MessageRow m;
    m.sender = std::move(sender);
    m.id = id;
    m.line = line;
    m.sent_s = number(field(fields, kSent), line, "sent_s");
    m.delivered_s = optional_number(field(fields, kDelivered), line, "delivered_s");
    m.acked_s = optional_number(field(fields, kAcked), line, "acked_s");
    if (m.delivered_s && *m.delivered_s < m.sent_s) {
      fail(line, field(fields, kDelivered).column, "delivered_s is before sent_s");
    }
    if (m.acked_s && *m.acked_s < m.sent_s) fail(line, field(fields, kAcked).column, "acked_s is before sent_s");
    const auto [it, inserted] = message_lines_.emplace(std::make_pair(m.sender, id), line);
    if (!inserted) {
      fail(line, field(fields, kId).column, "duplicate message " + std::to_string(id) + " of " + m.sender +
                                                " (first at line " + std::to_string(it->second) + ")");
    }
    log_.messages.push_back(std::move(m));
  }

  void read_cycle(const std::vector<Field>& fields, int line, std::string robot, std::int64_t id,
                  ManoeuvreKind kind) {
    require_empty(fields, line, {kSent, kDelivered, kAcked}, "on a manoeuvre row");
    CycleRow row;
    row.line = line;
    row.t_s = number(field(fields, kT), line, "t_s");
    row.cmd_trans_mps = number(field(fields, kCmdTrans), line, "cmd_trans_mps");
    row.cmd_rot_radps = number(field(fields, kCmdRot), line, "cmd_rot_radps");
    row.odom_x_m = number(field(fields, kOdomX), line, "odom_x_m");
    row.odom_y_m = number(field(fields, kOdomY), line, "odom_y_m");
    row.odom_theta_rad = number(field(fields, kOdomTheta), line, "odom_theta_rad");
    const std::array<Column, 3> truth_columns{kTrueX, kTrueY, kTrueTheta};
    const auto given = std::count_if(truth_columns.begin(), truth_columns.end(),
                                     [&](Column c) { return !field(fields, c).text.empty(); });
    if (given == 3) {
      row.truth = TruePose{number(field(fields, kTrueX), line, "true_x_m"), number(field(fields, kTrueY), line, "true_y_m"),
                           number(field(fields, kTrueTheta), line, "true_theta_rad")};
    } else if (given != 0) {
      const auto empty = std::find_if(truth_columns.begin(), truth_columns.end(),
                                      [&](Column c) { return field(fields, c).text.empty(); });
      fail(line, field(fields, *empty).column,
           "expected all three of true_x_m, true_y_m, true_theta_rad or none, got '" +
               calibration_log_columns()[*empty] + "' empty");
    }

    // The manoeuvre this row belongs to: the robot's current one, or a new one.
    const auto current = current_.find(robot);
    if (current != current_.end() && log_.manoeuvres[current->second].id == id) {
      Manoeuvre& m = log_.manoeuvres[current->second];
      if (m.kind != kind) {
        fail(line, field(fields, kKind).column, "manoeuvre " + std::to_string(id) + " of " + robot + " is a " +
                                                    to_string(m.kind) + " (line " + std::to_string(m.rows.front().line) +
                                                    "), this row says " + to_string(kind));
      }
      if (!(row.t_s > m.rows.back().t_s)) {
        fail(line, field(fields, kT).column, "t_s must increase within a manoeuvre (line " +
                                                 std::to_string(m.rows.back().line) + " has " +
                                                 show(std::to_string(m.rows.back().t_s)) + ")");
      }
      m.rows.push_back(row);
      return;
    }
    const auto [seen, inserted] = manoeuvre_lines_.emplace(std::make_pair(robot, id), line);
    if (!inserted) {
      fail(line, field(fields, kId).column, "manoeuvre " + std::to_string(id) + " of " + robot + " (started at line " +
                                                std::to_string(seen->second) +
                                                ") continues after another manoeuvre of " + robot +
                                                " (a manoeuvre's rows must not be split)");
    }
    Manoeuvre m;
    m.robot = robot;
    m.id = id;
    m.kind = kind;
    m.rows.push_back(row);
    current_[robot] = log_.manoeuvres.size();
    log_.manoeuvres.push_back(std::move(m));
  }

  std::string source_;
  std::array<std::size_t, kColumnCount> index_{};
  std::size_t width_ = 0;
  CalibrationLog log_;
  std::map<std::string, std::size_t> current_;                       ///< robot -> its latest manoeuvre
  std::map<std::pair<std::string, std::int64_t>, int> manoeuvre_lines_;  ///< first line of each manoeuvre
  std::map<std::pair<std::string, std::int64_t>, int> message_lines_;
};

}  // namespace

const char* to_string(ManoeuvreKind kind) {
  switch (kind) {
    case ManoeuvreKind::straight: return "straight";
    case ManoeuvreKind::spin: return "spin";
  }
  return "?";
}

const std::vector<std::string>& calibration_log_columns() {
  static const std::vector<std::string> kColumns{
      "robot",    "id",       "kind",           "t_s",      "cmd_trans_mps", "cmd_rot_radps",
      "odom_x_m", "odom_y_m", "odom_theta_rad", "true_x_m", "true_y_m",      "true_theta_rad",
      "sent_s",   "delivered_s", "acked_s"};
  return kColumns;
}

CalibrationLog parse_calibration_log(std::string_view text, const std::string& source_name) {
  return Reader(source_name).read(text);
}

CalibrationLog load_calibration_log(const std::string& path) {
  const auto cannot = [&path](const std::string& why) {
    return std::runtime_error(path + ": cannot read calibration log: " + why);
  };
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw cannot(ec && ec != std::errc::no_such_file_or_directory ? ec.message() : "no such file");
  }
  if (std::filesystem::is_directory(status)) throw cannot("it is a directory");
  if (!std::filesystem::is_regular_file(status)) throw cannot("not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw cannot(std::strerror(errno));
  std::string text;
  std::array<char, 65536> chunk{};
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxLogBytes) throw cannot("too large (limit " + std::to_string(kMaxLogBytes) + " bytes)");
  }
  if (in.bad()) throw cannot("read error");
  return parse_calibration_log(text, path);
}

}  // namespace p3at::verifier
