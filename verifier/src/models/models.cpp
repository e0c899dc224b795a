// The Models value type's members, its error type, and loading from a file.

#include <filesystem>
#include <string>

#include "models/text_file.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier {
namespace {

}  // namespace

const RobotModel* Models::find_robot(std::string_view name) const {
  for (const RobotModel& robot : robots) {
    if (robot.name == name) return &robot;
  }
  return nullptr;
}

Models load_models_file(const std::string& path) {
  std::string text;
  std::string why;
  if (!models_detail::read_text_file(path, text, why)) throw ModelsError(path, 0, 0, "cannot read models file: " + why);
  return parse_models(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace p3at::verifier
