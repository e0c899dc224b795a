#include "p3at/common/yaml_map.hpp"

#include <charconv>
#include <system_error>
#include <utility>

#include "p3at/common/yaml_document.hpp"

namespace p3at::yaml_reader {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

MapReader::MapReader(const Source& src, const YAML::Mark& mark, std::string where, std::string noun,
                     std::string path)
    : src_(&src), mark_(mark), where_(std::move(where)), noun_(std::move(noun)), path_(std::move(path)) {}

MapReader::MapReader(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string for_what,
                     std::string where, std::string noun, const std::vector<std::string>& allowed)
    : MapReader(src, node.IsNull() || !node.IsDefined() ? fallback : node.Mark(), std::move(where), std::move(noun),
                std::string()) {
  read(node, for_what, allowed);
}

MapReader MapReader::at_path(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string path,
                             const std::vector<std::string>& allowed) {
  const bool top = path.empty();
  MapReader map(src, node.IsNull() || !node.IsDefined() ? fallback : node.Mark(),
                top ? std::string("at the top level") : "in " + path, "key", path);
  map.read(node, top ? std::string("at the top level") : "for '" + path + "'", allowed);
  return map;
}

MapReader MapReader::empty(const Source& src, const YAML::Mark& mark, std::string where, std::string noun) {
  return MapReader(src, mark, std::move(where), std::move(noun), std::string());
}

void MapReader::read(const YAML::Node& node, const std::string& for_what, const std::vector<std::string>& allowed) {
  if (!node.IsMap()) src_->fail(mark_, "expected a mapping " + for_what + ", got " + describe(node));
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key_node = it->first;
    if (!key_node.IsScalar()) {
      src_->fail(key_node.Mark(), "expected a " + noun_ + " name " + where_ + ", got " + describe(key_node));
    }
    const std::string& key = key_node.Scalar();
    if (const Entry* first = find(key)) {
      src_->fail(key_node.Mark(), "duplicate " + noun_ + " '" + yaml_document::show(key) + "' " + where_ +
                                      " (first at " + position(first->key_node.Mark()) + ")");
    }
    bool known = false;
    for (const auto& name : allowed) known = known || name == key;
    if (!known) {
      src_->fail(key_node.Mark(), "unknown " + noun_ + " '" + yaml_document::show(key) + "' " + where_ +
                                      (allowed.empty() ? std::string(" (it takes none)")
                                                       : " (expected one of " + join(allowed) + ")"));
    }
    entries_.push_back(Entry{key, key_node, it->second});
  }
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

YAML::Node MapReader::get(std::string_view key) const { return entry(key).value; }

std::string MapReader::label(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string MapReader::scalar(std::string_view key, std::string_view expected) const {
  const Entry& e = entry(key);
  if (!e.value.IsScalar()) {
    src_->fail(value_mark(key), "expected " + std::string(expected) + " for '" + label(key) + "', got " +
                                    describe(e.value));
  }
  return e.value.Scalar();
}

double MapReader::number(std::string_view key, const Range& range) const {
  return read_number(*src_, entry(key).value, value_mark(key), label(key), range);
}

double MapReader::number_or(std::string_view key, const Range& range, double fallback) const {
  return has(key) ? number(key, range) : fallback;
}

std::int64_t MapReader::integer(std::string_view key, std::int64_t lo, std::int64_t hi) const {
  const Entry& e = entry(key);
  const std::string text = scalar(key, "an integer");
  const std::string_view digits = strip_plus(text);
  std::int64_t value = 0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && result.ptr == digits.data() + digits.size();
  const bool too_big = result.ec == std::errc::result_out_of_range && whole;
  if (!may_be_number(e.value) || !whole || (result.ec != std::errc() && !too_big)) {
    src_->fail(value_mark(key), "expected an integer for '" + label(key) + "', got " + describe(e.value));
  }
  if (too_big || value < lo || value > hi) {
    src_->fail(value_mark(key), "'" + label(key) + "' out of range: " + yaml_document::show(text) + " (expected " +
                                    std::to_string(lo) + " <= " + std::string(key) + " <= " + std::to_string(hi) +
                                    ")");
  }
  return value;
}

std::int64_t MapReader::integer_or(std::string_view key, std::int64_t lo, std::int64_t hi,
                                   std::int64_t fallback) const {
  return has(key) ? integer(key, lo, hi) : fallback;
}

std::string MapReader::string(std::string_view key) const { return scalar(key, "a string"); }

bool MapReader::boolean(std::string_view key) const {
  const Entry& e = entry(key);
  if (e.value.IsScalar() && e.value.Tag() == "?") {
    if (e.value.Scalar() == "true") return true;
    if (e.value.Scalar() == "false") return false;
  }
  src_->fail(value_mark(key), "expected true or false for '" + label(key) + "', got " + describe(e.value));
}

YAML::Node MapReader::sequence(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.value.IsSequence()) {
    src_->fail(value_mark(key), "expected a list for '" + label(key) + "', got " + describe(e.value));
  }
  return e.value;
}

MapReader MapReader::map(std::string_view key, std::string where, const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  return MapReader(*src_, e.value, e.key_node.Mark(), "for '" + label(key) + "'", std::move(where), "key", allowed);
}

MapReader MapReader::params(std::string_view key, std::string where, const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  return MapReader(*src_, e.value, e.key_node.Mark(), "for '" + label(key) + "'", std::move(where), "parameter",
                   allowed);
}

MapReader MapReader::map_at(std::string_view key, const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  return at_path(*src_, e.value, e.key_node.Mark(), label(key), allowed);
}

}  // namespace p3at::yaml_reader
