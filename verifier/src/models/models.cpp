// The Models value type's members, its error type, and loading from a file.

#include <filesystem>
#include <string>

#include "models/text_file.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier {
namespace {

std::string format_error(const std::string& file, int line, int column, const std::string& detail) {
  if (line <= 0) return file + ": " + detail;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + detail;
}

}  // namespace

ModelsError::ModelsError(std::string file, int line, int column, std::string detail)
    : std::runtime_error(format_error(file, line, column, detail)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      detail_(std::move(detail)) {}

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
