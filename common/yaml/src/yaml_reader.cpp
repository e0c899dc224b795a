#include "p3at/common/yaml_reader.hpp"

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
  return format_shortest(lo) + (lo_open ? " < " : " <= ") + std::string(what) + (hi_open ? " < " : " <= ") +
         format_shortest(hi);
}

}  // namespace p3at::yaml_reader
