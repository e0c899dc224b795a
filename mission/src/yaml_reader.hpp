#pragma once
// Typed, located access to yaml-cpp nodes for the mission loader: every read
// checks type and range and, on failure, throws MissionError at the node. The
// mapping reader and the pieces shared with the other readers are common/yaml's
// (yaml_map.hpp, yaml_reader.hpp); this file adds what only missions have.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_map.hpp"
#include "p3at/common/yaml_reader.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/mission/names.hpp"

namespace p3at::mission::detail {

/// Where errors are reported: throws MissionError at a node (the loader
/// makes it a yaml_reader::SourceOf<MissionError>).
using Source = yaml_reader::Source;
using MissionSource = yaml_reader::SourceOf<MissionError>;
/// The shared mapping reader (common/yaml): a mission names keys alone.
using yaml_reader::MapReader;
using yaml_reader::describe;
using yaml_reader::join;
using yaml_reader::position;
using yaml_reader::Range;

/// A name: 1 to 64 letters, digits or '_', not starting with a digit. `kind` names it in messages.
std::string read_name(const MapReader& map, std::string_view key, std::string_view kind);
/// A list of exactly two numbers [x, y], each in `range`.
Point2 read_point(const MapReader& map, std::string_view key, const Range& range);

/// `items` joined by ", ", at most `max_items` of them, then "...".
std::string join_some(const std::vector<std::string>& items, std::size_t max_items = 12);
/// User text made safe to echo in a one-line message: control bytes escaped, long text cut.
std::string show(std::string_view text);


}  // namespace p3at::mission::detail
