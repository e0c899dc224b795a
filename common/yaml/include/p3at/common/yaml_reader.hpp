#pragma once
// Typed, located reading of yaml-cpp nodes: the pieces every YAML reader of
// the project shares (the mission loader, the verifier's robot-models
// reader, the simulator's world loader): where an error is, what a node is,
// numeric ranges, checked numbers. Each reader throws its own LocatedError
// subclass through a SourceOf<Error>; the readers' code sees only Source.
// The mapping reader built on these is yaml_map.hpp.

#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <string>
#include <string_view>
#include <utility>

namespace p3at::yaml_reader {

/// Where errors are reported: the source's name; fail() throws the reader's
/// error (see SourceOf) with the mark's 1-based line and column, or with no
/// position for a null mark.
class Source {
 public:
  explicit Source(std::string name) : name_(std::move(name)) {}
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;
  virtual ~Source() = default;

  [[noreturn]] void fail(const YAML::Mark& mark, std::string detail) const {
    if (mark.is_null()) {
      raise(0, 0, std::move(detail));
    } else {
      raise(mark.line + 1, mark.column + 1, std::move(detail));
    }
    std::abort();  // not reached: raise() throws (a virtual call's [[noreturn]] is not seen by the compiler)
  }
  const std::string& name() const { return name_; }

 protected:
  /// Throws the reader's error; line 0 when there is no position.
  [[noreturn]] virtual void raise(int line, int column, std::string detail) const = 0;

 private:
  std::string name_;
};

/// A Source whose errors are `Error`, constructed as Error(name, line, column,
/// detail) (a LocatedError subclass, or any type with that constructor).
template <class Error>
class SourceOf final : public Source {
 public:
  using Source::Source;

 protected:
  [[noreturn]] void raise(int line, int column, std::string detail) const override {
    throw Error(name(), line, column, std::move(detail));
  }
};

/// "line:column", 1-based.
std::string position(const YAML::Mark& mark);
/// What a node is, for "got ..." in messages: "a mapping", "null", "'abc'", ...
std::string describe(const YAML::Node& node);
/// A scalar that may be read as a number: plain (YAML resolves its type from
/// its text) or explicitly tagged !!int / !!float. A quoted "2" is a string.
bool may_be_number(const YAML::Node& node);

/// A closed or open numeric interval, rendered in messages as "0 < x <= 1";
/// with one infinite bound, by its finite one alone ("x > 0").
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const;
  std::string describe(std::string_view what) const;
};

/// A plain (or !!int/!!float tagged) scalar read as a finite number in
/// `range`; else fails at `mark`: "expected a number for 'label', got ..." or
/// "'label' out of range: text (expected lo <= key <= hi)", where key is the
/// last dotted part of `label` ("cycle_s" of "robots[0].kinematics.cycle_s").
double read_number(const Source& src, const YAML::Node& node, const YAML::Mark& mark, const std::string& label,
                   const Range& range);

/// `text` without a leading '+' (YAML allows one; std::from_chars does not).
std::string_view strip_plus(std::string_view text);

}  // namespace p3at::yaml_reader
