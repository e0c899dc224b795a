#include "yaml_reader.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "p3at/mission/loader.hpp"
#include "p3at/common/yaml_document.hpp"

namespace p3at::mission::detail {

// User text echoed in a message is shortened and every byte outside printable
// ASCII escaped (names are ASCII anyway), so an error is always one readable line.
std::string show(std::string_view text) { return yaml_document::show(text); }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

std::string join_some(const std::vector<std::string>& items, std::size_t max_items) {
  if (items.size() <= max_items) return join(items);
  std::vector<std::string> head(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(max_items));
  return join(head) + ", ...";
}

MapReader::MapReader(const Source& src, const YAML::Node& node, const YAML::Mark& fallback,
                     std::string for_what, std::string where, std::string noun,
                     const std::vector<std::string>& allowed)
    : src_(&src), mark_(node.IsNull() ? fallback : node.Mark()), where_(std::move(where)),
      noun_(std::move(noun)) {
  if (!node.IsMap()) src.fail(mark_, "expected a mapping " + for_what + ", got " + describe(node));
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key_node = it->first;
    if (!key_node.IsScalar()) {
      src.fail(key_node.Mark(), "expected a " + noun_ + " name " + where_ + ", got " + describe(key_node));
    }
    const std::string& key = key_node.Scalar();
    if (const Entry* first = find(key)) {
      src.fail(key_node.Mark(), "duplicate " + noun_ + " '" + show(key) + "' " + where_ +
                                    " (first at " + position(first->key_node.Mark()) + ")");
    }
    bool known = false;
    for (const auto& name : allowed) known = known || name == key;
    if (!known) {
      src.fail(key_node.Mark(), "unknown " + noun_ + " '" + show(key) + "' " + where_ +
                                    (allowed.empty() ? std::string(" (it takes none)")
                                                     : " (expected one of " + join(allowed) + ")"));
    }
    entries_.push_back(Entry{key, key_node, it->second});
  }
}

MapReader::MapReader(const Source& src, const YAML::Mark& mark, std::string where, std::string noun)
    : src_(&src), mark_(mark), where_(std::move(where)), noun_(std::move(noun)) {}

MapReader MapReader::empty(const Source& src, const YAML::Mark& mark, std::string where, std::string noun) {
  return MapReader(src, mark, std::move(where), std::move(noun));
}

const MapReader::Entry* MapReader::find(std::string_view key) const {
  for (const auto& e : entries_) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

const MapReader::Entry& MapReader::entry(std::string_view key) const {
  const Entry* e = find(key);
  if (e == nullptr) src_->fail(mark_, "missing required " + noun_ + " '" + std::string(key) + "' " + where_);
  return *e;
}

bool MapReader::has(std::string_view key) const { return find(key) != nullptr; }

YAML::Mark MapReader::key_mark(std::string_view key) const { return entry(key).key_node.Mark(); }

YAML::Mark MapReader::value_mark(std::string_view key) const {
  const Entry& e = entry(key);
  return e.value.IsNull() ? e.key_node.Mark() : e.value.Mark();
}

YAML::Node MapReader::require(std::string_view key) const { return entry(key).value; }
YAML::Node MapReader::get(std::string_view key) const { return entry(key).value; }

std::string MapReader::scalar(std::string_view key, std::string_view expected) const {
  const Entry& e = entry(key);
  if (!e.value.IsScalar()) {
    src_->fail(value_mark(key), "expected " + std::string(expected) + " for '" + std::string(key) +
                                    "', got " + describe(e.value));
  }
  return e.value.Scalar();
}

namespace {

// YAML allows a leading '+'; from_chars does not.
std::string_view strip_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

// Reads a plain scalar as a finite double and range-checks it; `label` names it in messages.
double checked_number(const Source& src, const YAML::Node& node, const YAML::Mark& mark,
                      std::string_view label, const Range& range) {
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  const std::string_view digits = strip_plus(text);
  double value = 0.0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool parsed = result.ec == std::errc() && result.ptr == digits.data() + digits.size();
  if (!node.IsScalar() || !yaml_reader::may_be_number(node) || !parsed || !std::isfinite(value)) {
    src.fail(mark, "expected a number for '" + std::string(label) + "', got " + describe(node));
  }
  if (!range.contains(value)) {
    src.fail(mark, "'" + std::string(label) + "' out of range: " + show(text) + " (expected " +
                       range.describe(label) + ")");
  }
  return value;
}

}  // namespace

double MapReader::number(std::string_view key, const Range& range) const {
  return checked_number(*src_, entry(key).value, value_mark(key), key, range);
}

double MapReader::number_or(std::string_view key, const Range& range, double fallback) const {
  return has(key) ? number(key, range) : fallback;
}

std::int64_t MapReader::integer_or(std::string_view key, std::int64_t lo, std::int64_t hi,
                                   std::int64_t fallback) const {
  if (!has(key)) return fallback;
  const Entry& e = entry(key);
  const std::string text = scalar(key, "an integer");
  const std::string_view digits = strip_plus(text);
  std::int64_t value = 0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = result.ptr == digits.data() + digits.size();
  const bool range_error = result.ec == std::errc::result_out_of_range && whole;
  if (!yaml_reader::may_be_number(e.value) || !whole || (result.ec != std::errc() && !range_error)) {
    src_->fail(value_mark(key), "expected an integer for '" + std::string(key) + "', got " + describe(e.value));
  }
  if (range_error || value < lo || value > hi) {
    src_->fail(value_mark(key), "'" + std::string(key) + "' out of range: " + show(text) + " (expected " +
                                    std::to_string(lo) + " <= " + std::string(key) + " <= " +
                                    std::to_string(hi) + ")");
  }
  return value;
}

std::string MapReader::string(std::string_view key) const { return scalar(key, "a string"); }

std::string MapReader::name(std::string_view key, std::string_view kind) const {
  std::string text = scalar(key, "a name");
  if (!is_valid_name(text)) {
    src_->fail(value_mark(key), "invalid " + std::string(kind) + " name '" + show(text) +
                                    "' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  }
  return text;
}

Point2 MapReader::point(std::string_view key, const Range& range) const {
  const Entry& e = entry(key);
  const std::string expected = "expected a list of 2 numbers [x_m, y_m] for '" + std::string(key) + "'";
  if (!e.value.IsSequence()) src_->fail(value_mark(key), expected + ", got " + describe(e.value));
  if (e.value.size() != 2) {
    src_->fail(value_mark(key), expected + ", got " + std::to_string(e.value.size()) +
                                    (e.value.size() == 1 ? " element" : " elements"));
  }
  // Each element is checked like a key of its own, so messages name it goal[0], goal[1].
  std::array<double, 2> xy{};
  for (std::size_t i = 0; i < 2; ++i) {
    const YAML::Node element = e.value[i];
    const YAML::Mark element_mark = element.IsNull() ? e.value.Mark() : element.Mark();
    xy[i] = checked_number(*src_, element, element_mark, std::string(key) + "[" + std::to_string(i) + "]", range);
  }
  return Point2{xy[0], xy[1]};
}

MapReader MapReader::map(std::string_view key, std::string where, const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  return MapReader(*src_, e.value, e.key_node.Mark(), "for '" + std::string(key) + "'", std::move(where),
                   "key", allowed);
}

MapReader MapReader::params(std::string_view key, std::string where, const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  return MapReader(*src_, e.value, e.key_node.Mark(), "for '" + std::string(key) + "'", std::move(where),
                   "parameter", allowed);
}

YAML::Node MapReader::sequence(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.value.IsSequence()) {
    src_->fail(value_mark(key), "expected a list for '" + std::string(key) + "', got " + describe(e.value));
  }
  return e.value;
}

}  // namespace p3at::mission::detail
