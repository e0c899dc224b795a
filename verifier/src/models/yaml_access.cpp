#include "models/yaml_access.hpp"

#include <string>

#include "p3at/common/yaml_document.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::models_detail {

YAML::Node load_document(const Source& src, std::string_view text, std::string_view what) {
  try {
    return yaml_document::load_single(text, "empty " + std::string(what));
  } catch (const yaml_document::Problem& problem) {
    src.fail(problem.mark, problem.detail);
  }
}

std::string show(std::string_view text, std::size_t max_chars) { return yaml_document::show(text, max_chars); }

}  // namespace p3at::verifier::models_detail
