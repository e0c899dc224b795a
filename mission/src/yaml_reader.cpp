#include "yaml_reader.hpp"

#include <array>

#include "p3at/common/yaml_document.hpp"
#include "p3at/mission/loader.hpp"

namespace p3at::mission::detail {

// User text echoed in a message is shortened and every byte outside printable
// ASCII escaped (names are ASCII anyway), so an error is always one readable line.
std::string show(std::string_view text) { return yaml_document::show(text); }

std::string join_some(const std::vector<std::string>& items, std::size_t max_items) {
  if (items.size() <= max_items) return join(items);
  std::vector<std::string> head(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(max_items));
  return join(head) + ", ...";
}

std::string read_name(const MapReader& map, std::string_view key, std::string_view kind) {
  const YAML::Node value = map.get(key);
  if (!value.IsScalar()) {
    map.source().fail(map.value_mark(key), "expected a name for '" + map.label(key) + "', got " + describe(value));
  }
  std::string text = value.Scalar();
  if (!is_valid_name(text)) {
    map.source().fail(map.value_mark(key), "invalid " + std::string(kind) + " name '" + show(text) +
                                               "' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  }
  return text;
}

Point2 read_point(const MapReader& map, std::string_view key, const Range& range) {
  const YAML::Node value = map.get(key);
  const Source& src = map.source();
  const std::string expected = "expected a list of 2 numbers [x_m, y_m] for '" + map.label(key) + "'";
  if (!value.IsSequence()) src.fail(map.value_mark(key), expected + ", got " + describe(value));
  if (value.size() != 2) {
    src.fail(map.value_mark(key), expected + ", got " + std::to_string(value.size()) +
                                      (value.size() == 1 ? " element" : " elements"));
  }
  // Each element is checked like a key of its own, so messages name it goal[0], goal[1].
  std::array<double, 2> xy{};
  for (std::size_t i = 0; i < 2; ++i) {
    const YAML::Node element = value[i];
    const YAML::Mark element_mark = element.IsNull() ? value.Mark() : element.Mark();
    xy[i] = yaml_reader::read_number(src, element, element_mark, map.label(key) + "[" + std::to_string(i) + "]",
                                     range);
  }
  return Point2{xy[0], xy[1]};
}

}  // namespace p3at::mission::detail
