#include "document.hpp"

#include <string>

#include "p3at/common/yaml_document.hpp"

namespace p3at::mission::detail {
namespace {

const char* const kEmpty = "empty mission (expected a mapping with keys mission, criteria, robots, messages)";

}  // namespace

YAML::Node load_single_document(const Source& src, std::string_view text) {
  try {
    return yaml_document::load_single(text, kEmpty);
  } catch (const yaml_document::Problem& problem) {
    src.fail(problem.mark, problem.detail);
  }
}

}  // namespace p3at::mission::detail
