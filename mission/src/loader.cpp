#include "p3at/mission/loader.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "document.hpp"
#include "mission_reader.hpp"
#include "yaml_reader.hpp"

namespace p3at::mission {
namespace {

// Larger than any sensible mission; keeps a wrong path (a log, a disk image) from being slurped.
constexpr std::streamoff kMaxFileBytes = 16 * 1024 * 1024;

}  // namespace

Mission parse_mission(std::string_view yaml_text, const std::string& source_name) {
  const detail::MissionSource src(source_name);
  const YAML::Node root = detail::load_single_document(src, yaml_text);
  try {
    return detail::read_mission(src, root);
  } catch (const YAML::Exception& e) {
    // yaml-cpp should not throw while we walk a loaded tree; if it does, still a located error.
    src.fail(e.mark, "malformed YAML: " + e.msg);
  }
}

Mission load_mission_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw MissionError(path, 0, 0, "cannot open mission file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MissionError(path, 0, 0, std::string("cannot open mission file: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size > kMaxFileBytes) {
    throw MissionError(path, 0, 0, "mission file too large (" + std::to_string(size) + " bytes, limit " +
                                       std::to_string(kMaxFileBytes) + ")");
  }
  in.seekg(0, std::ios::beg);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw MissionError(path, 0, 0, "cannot read mission file");
  return parse_mission(text.str(), path);
}

}  // namespace p3at::mission
