#pragma once
// Typed, located reading of yaml-cpp nodes: the pieces every YAML reader of
// the project shares (the mission loader, the verifier's robot-models
// reader): where an error is, what a node is, numeric ranges. Each reader
// keeps its own mapping reader (their messages name keys differently) and
// throws its own LocatedError subclass through Source<Error>.

#include <yaml-cpp/yaml.h>

#include <string>
#include <string_view>
#include <utility>

namespace p3at::yaml_reader {

/// Where errors are reported: the source's name; fail() throws `Error` (a
/// LocatedError subclass) with the mark's 1-based line and column.
template <class Error>
class Source {
 public:
  explicit Source(std::string name) : name_(std::move(name)) {}
  [[noreturn]] void fail(const YAML::Mark& mark, std::string detail) const {
    if (mark.is_null()) throw Error(name_, 0, 0, std::move(detail));
    throw Error(name_, mark.line + 1, mark.column + 1, std::move(detail));
  }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

/// "line:column", 1-based.
std::string position(const YAML::Mark& mark);
/// What a node is, for "got ..." in messages: "a mapping", "null", "'abc'", ...
std::string describe(const YAML::Node& node);
/// A scalar that may be read as a number: plain (YAML resolves its type from
/// its text) or explicitly tagged !!int / !!float. A quoted "2" is a string.
bool may_be_number(const YAML::Node& node);

/// A closed or open numeric interval, rendered in messages as "0 < x <= 1".
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const;
  std::string describe(std::string_view what) const;
};

}  // namespace p3at::yaml_reader
