#pragma once
// The one reader of a YAML mapping with a fixed set of keys, shared by the
// mission loader, the verifier's robot-models reader and the simulator's world
// loader: construction checks
// it is a mapping with no duplicate and no unknown key; every getter checks
// the value's type and range; every failure is the reader's LocatedError at
// the node, saying what was expected.
//
// Two ways of naming keys in messages, one per file format:
//  - by the key alone, with the mapping described in words (missions and
//    worlds: "unknown key 'x' in robot", "expected a number for 'max_speed_mps'");
//  - by a dotted path from the top (robot models: "robots[0].motion.cycle_s").

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/yaml_reader.hpp"

namespace p3at::yaml_reader {

class MapReader {
 public:
  /// A mapping whose keys are named alone. `for_what` completes "expected a
  /// mapping ..." (e.g. "for 'criteria'"); `where` completes "unknown key 'k'
  /// ..." (e.g. "in criteria"); `noun` is "key" or "parameter". `fallback`
  /// locates a null node.
  MapReader(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string for_what,
            std::string where, std::string noun, const std::vector<std::string>& allowed);

  /// A mapping named by its dotted `path` from the top ("robots[0].motion";
  /// empty for the top level): its keys are named "path.key" in messages.
  static MapReader at_path(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string path,
                           const std::vector<std::string>& allowed);

  /// An empty mapping standing in for an absent optional one (e.g. no
  /// `params:`), with errors such as a missing key reported at `mark`.
  static MapReader empty(const Source& src, const YAML::Mark& mark, std::string where, std::string noun);

  bool has(std::string_view key) const;
  /// Where the mapping starts (or its fallback).
  const YAML::Mark& mark() const { return mark_; }
  /// Mark of the key itself; "missing required ..." if absent.
  YAML::Mark key_mark(std::string_view key) const;
  /// Mark of the value, or of its key if the value is null (yaml-cpp puts a
  /// null's mark at the next token, which is misleading).
  YAML::Mark value_mark(std::string_view key) const;
  /// The value; "missing required <noun> 'key' <where>" if absent.
  YAML::Node get(std::string_view key) const;
  /// The key as messages name it: "path.key", or the key alone.
  std::string label(std::string_view key) const;

  double number(std::string_view key, const Range& range) const;
  double number_or(std::string_view key, const Range& range, double fallback) const;
  std::int64_t integer(std::string_view key, std::int64_t lo, std::int64_t hi) const;
  std::int64_t integer_or(std::string_view key, std::int64_t lo, std::int64_t hi, std::int64_t fallback) const;
  /// Any string scalar (plain or quoted).
  std::string string(std::string_view key) const;
  /// A plain `true` or `false` (a quoted "true" is a string, as a quoted "2" is not a number).
  bool boolean(std::string_view key) const;
  /// A list; fails if the value is not a sequence.
  YAML::Node sequence(std::string_view key) const;

  /// A nested mapping named by its key alone, unknown keys reported `where`.
  MapReader map(std::string_view key, std::string where, const std::vector<std::string>& allowed) const;
  /// The same, its keys called "parameter"s.
  MapReader params(std::string_view key, std::string where, const std::vector<std::string>& allowed) const;
  /// A nested mapping named by its path, "path.key".
  MapReader map_at(std::string_view key, const std::vector<std::string>& allowed) const;

  const Source& source() const { return *src_; }

 private:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  MapReader(const Source& src, const YAML::Mark& mark, std::string where, std::string noun, std::string path);
  void read(const YAML::Node& node, const std::string& for_what, const std::vector<std::string>& allowed);
  const Entry* find(std::string_view key) const;
  const Entry& entry(std::string_view key) const;
  std::string scalar(std::string_view key, std::string_view expected) const;

  const Source* src_;
  YAML::Mark mark_;
  std::string where_;
  std::string noun_;
  std::string path_;
  std::vector<Entry> entries_;
};

/// "a, b, c".
std::string join(const std::vector<std::string>& items);

}  // namespace p3at::yaml_reader
