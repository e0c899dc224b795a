#pragma once
// Typed, located access to yaml-cpp nodes for the mission loader: every read
// checks type and range and, on failure, throws MissionError at the node. The
// pieces shared with the other readers are common/yaml's yaml_reader.hpp.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_reader.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/mission/names.hpp"

namespace p3at::mission::detail {

/// Where errors are reported: throws MissionError at a node.
using Source = yaml_reader::Source<MissionError>;
using yaml_reader::describe;
using yaml_reader::position;
using yaml_reader::Range;

/// "a, b, c".
std::string join(const std::vector<std::string>& items);

/// A YAML mapping with a fixed set of allowed keys. Construction checks it is a
/// mapping with no duplicate and no unknown keys; getters check each value.
class MapReader {
 public:
  /// `for_what`: completes "expected a mapping ..." (e.g. "for 'criteria'");
  /// `where`: completes "unknown key 'k' ..." (e.g. "in criteria");
  /// `noun`: "key" or "parameter". `fallback` locates a null node.
  MapReader(const Source& src, const YAML::Node& node, const YAML::Mark& fallback,
            std::string for_what, std::string where, std::string noun,
            const std::vector<std::string>& allowed);
  /// A nested mapping whose unknown keys are "parameter"s `where` (e.g. "for behavior Spin").
  MapReader params(std::string_view key, std::string where, const std::vector<std::string>& allowed) const;

  /// An empty mapping standing in for an absent optional one (e.g. no `params:`),
  /// with errors such as a missing parameter reported at `mark`.
  static MapReader empty(const Source& src, const YAML::Mark& mark, std::string where, std::string noun);

  bool has(std::string_view key) const;
  const YAML::Mark& mark() const { return mark_; }
  /// Mark of the key itself (precondition: has(key)).
  YAML::Mark key_mark(std::string_view key) const;
  /// Mark of the value, or of its key if the value is null (yaml-cpp puts a
  /// null's mark at the next token, which is misleading).
  YAML::Mark value_mark(std::string_view key) const;
  /// The value; throws "missing required ..." if absent.
  YAML::Node require(std::string_view key) const;
  /// The value (precondition: has(key)).
  YAML::Node get(std::string_view key) const;

  double number(std::string_view key, const Range& range) const;
  double number_or(std::string_view key, const Range& range, double fallback) const;
  std::int64_t integer_or(std::string_view key, std::int64_t lo, std::int64_t hi,
                          std::int64_t fallback) const;
  /// Any string scalar (plain or quoted).
  std::string string(std::string_view key) const;
  /// A name: 1 to 64 letters, digits or '_', not starting with a digit. `kind` names it in messages.
  std::string name(std::string_view key, std::string_view kind) const;
  /// A list of exactly two numbers [x, y], each in `range`.
  Point2 point(std::string_view key, const Range& range) const;
  /// A nested mapping.
  MapReader map(std::string_view key, std::string where, const std::vector<std::string>& allowed) const;
  /// A list; throws if the value is not a sequence.
  YAML::Node sequence(std::string_view key) const;

  const Source& source() const { return *src_; }

 private:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  const Entry* find(std::string_view key) const;
  const Entry& entry(std::string_view key) const;
  MapReader(const Source& src, const YAML::Mark& mark, std::string where, std::string noun);
  std::string scalar(std::string_view key, std::string_view expected) const;

  const Source* src_;
  YAML::Mark mark_;
  std::string where_;
  std::string noun_;
  std::vector<Entry> entries_;
};

/// `items` joined by ", ", at most `max_items` of them, then "...".
std::string join_some(const std::vector<std::string>& items, std::size_t max_items = 12);
/// User text made safe to echo in a one-line message: control bytes escaped, long text cut.
std::string show(std::string_view text);


}  // namespace p3at::mission::detail
