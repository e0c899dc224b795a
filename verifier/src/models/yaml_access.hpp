#pragma once
// Typed, located reading of yaml-cpp nodes for the robot-models file: every
// read checks the type and range and, on failure, throws ModelsError at the
// node with what was expected. The pieces shared with the mission loader are
// common/yaml's yaml_reader.hpp; the mapping reader is this file's own (its
// messages name keys by path, "robots[0].motion.cycle_s").

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_reader.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::models_detail {

/// Where errors are reported: throws ModelsError, "file:line:column: detail".
using Source = yaml_reader::Source<ModelsError>;
using yaml_reader::describe;
using yaml_reader::position;
using yaml_reader::Range;

/// The root of the one non-empty YAML document in `text`; `what` completes
/// "empty <what>" when there is none. Throws ModelsError for malformed YAML
/// (guarding yaml-cpp 0.7's endless loop on a stray ',') or a second document.
YAML::Node load_document(const Source& src, std::string_view text, std::string_view what);

/// User text made safe to echo in a one-line message: control and non-ASCII
/// bytes escaped, cut after `max_chars`.
std::string show(std::string_view text, std::size_t max_chars = 48);

/// A finite number in `range`; `label` names it in messages.
double read_number(const Source& src, const YAML::Node& node, const YAML::Mark& mark, const std::string& label,
                   const Range& range);

/// A mapping with a fixed set of allowed keys; construction rejects anything
/// else, duplicate keys and unknown keys. `path` names it in messages
/// ("robots[0].motion"; empty for the top level).
class Map {
 public:
  Map(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string path,
      const std::vector<std::string_view>& allowed);

  bool has(std::string_view key) const;
  /// Where the mapping starts.
  const YAML::Mark& mark() const { return mark_; }
  /// The value's mark, or its key's if the value is null (yaml-cpp puts a
  /// null's mark at the next token).
  YAML::Mark value_mark(std::string_view key) const;
  /// The value; "missing required key" if absent.
  YAML::Node get(std::string_view key) const;
  /// "path.key", for messages.
  std::string label(std::string_view key) const;

  double number(std::string_view key, const Range& range) const;
  double number_or(std::string_view key, const Range& range, double fallback) const;
  std::int64_t integer(std::string_view key, std::int64_t lo, std::int64_t hi) const;
  std::string string(std::string_view key) const;
  /// A nested mapping, its path "path.key".
  Map map(std::string_view key, const std::vector<std::string_view>& allowed) const;
  /// A list (a YAML sequence).
  YAML::Node list(std::string_view key) const;

  const Source& source() const { return *src_; }

 private:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  const Entry* find(std::string_view key) const;
  const Entry& entry(std::string_view key) const;

  const Source* src_;
  YAML::Mark mark_;
  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace p3at::verifier::models_detail
