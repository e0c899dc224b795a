#include "p3at/common/yaml_reader.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_document.hpp"

namespace p3at::yaml_reader {

std::string position(const YAML::Mark& mark) {
  return std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Undefined: return "nothing";
    case YAML::NodeType::Null: return "null";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Scalar:
      if (node.Tag() == "?") return "'" + yaml_document::show(node.Scalar()) + "'";
      if (node.Tag() == "!") return "the quoted string \"" + yaml_document::show(node.Scalar()) + "\"";
      return "'" + yaml_document::show(node.Scalar()) + "' tagged " + yaml_document::show(node.Tag());
  }
  return "something else";
}

bool may_be_number(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float";
}

bool Range::contains(double v) const {
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::describe(std::string_view what) const {
  // A range open on one side ("> 0", as the world file's scales) names only its finite bound.
  const bool no_lo = std::isinf(lo) && lo < 0.0;
  const bool no_hi = std::isinf(hi) && hi > 0.0;
  if (no_hi && !no_lo) return std::string(what) + (lo_open ? " > " : " >= ") + format_shortest(lo);
  if (no_lo && !no_hi) return std::string(what) + (hi_open ? " < " : " <= ") + format_shortest(hi);
  return format_shortest(lo) + (lo_open ? " < " : " <= ") + std::string(what) + (hi_open ? " < " : " <= ") +
         format_shortest(hi);
}

std::string_view strip_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

double read_number(const Source& src, const YAML::Node& node, const YAML::Mark& mark, const std::string& label,
                   const Range& range) {
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  const std::string_view digits = strip_plus(text);
  double value = 0.0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool parsed = result.ec == std::errc() && result.ptr == digits.data() + digits.size();
  if (!node.IsScalar() || !may_be_number(node) || !parsed || !std::isfinite(value)) {
    src.fail(mark, "expected a number for '" + label + "', got " + describe(node));
  }
  if (!range.contains(value)) {
    const std::size_t dot = label.rfind('.');
    const std::string_view key = dot == std::string::npos ? std::string_view(label)
                                                          : std::string_view(label).substr(dot + 1);
    src.fail(mark, "'" + label + "' out of range: " + yaml_document::show(text) + " (expected " +
                       range.describe(key) + ")");
  }
  return value;
}

}  // namespace p3at::yaml_reader
