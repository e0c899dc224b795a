#include "models/yaml_access.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

#include "p3at/common/yaml_document.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::models_detail {
namespace {

// YAML allows a leading '+'; from_chars does not.
std::string_view strip_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

std::string join(const std::vector<std::string_view>& items) {
  std::string out;
  for (std::string_view item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

// The last part of a label ("cycle_s" of "robots[0].kinematics.cycle_s").
std::string_view last_part(std::string_view label) {
  const std::size_t dot = label.rfind('.');
  return dot == std::string_view::npos ? label : label.substr(dot + 1);
}

}  // namespace

YAML::Node load_document(const Source& src, std::string_view text, std::string_view what) {
  try {
    return yaml_document::load_single(text, "empty " + std::string(what));
  } catch (const yaml_document::Problem& problem) {
    src.fail(problem.mark, problem.detail);
  }
}

std::string show(std::string_view text, std::size_t max_chars) { return yaml_document::show(text, max_chars); }

double read_number(const Source& src, const YAML::Node& node, const YAML::Mark& mark, const std::string& label,
                   const Range& range) {
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  const std::string_view digits = strip_plus(text);
  double value = 0.0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool parsed = result.ec == std::errc() && result.ptr == digits.data() + digits.size();
  if (!node.IsScalar() || !yaml_reader::may_be_number(node) || !parsed || !std::isfinite(value)) {
    src.fail(mark, "expected a number for '" + label + "', got " + describe(node));
  }
  if (!range.contains(value)) {
    src.fail(mark, "'" + label + "' out of range: " + show(text) + " (expected " + range.describe(last_part(label)) + ")");
  }
  return value;
}

Map::Map(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, std::string path,
         const std::vector<std::string_view>& allowed)
    : src_(&src), mark_(node.IsNull() || !node.IsDefined() ? fallback : node.Mark()), path_(std::move(path)) {
  const std::string where = path_.empty() ? std::string("at the top level") : "in " + path_;
  if (!node.IsMap()) {
    src.fail(mark_, "expected a mapping " + (path_.empty() ? std::string("at the top level") : "for '" + path_ + "'") +
                        ", got " + describe(node));
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key_node = it->first;
    if (!key_node.IsScalar()) src.fail(key_node.Mark(), "expected a key name " + where + ", got " + describe(key_node));
    const std::string& key = key_node.Scalar();
    if (const Entry* first = find(key)) {
      src.fail(key_node.Mark(),
               "duplicate key '" + show(key) + "' " + where + " (first at " + position(first->key_node.Mark()) + ")");
    }
    bool known = false;
    for (std::string_view name : allowed) known = known || name == key;
    if (!known) {
      src.fail(key_node.Mark(), "unknown key '" + show(key) + "' " + where + " (expected one of " + join(allowed) + ")");
    }
    entries_.push_back(Entry{key, key_node, it->second});
  }
}

const Map::Entry* Map::find(std::string_view key) const {
  for (const Entry& e : entries_) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

const Map::Entry& Map::entry(std::string_view key) const {
  const Entry* e = find(key);
  if (e == nullptr) {
    src_->fail(mark_, "missing required key '" + std::string(key) + "' " +
                          (path_.empty() ? std::string("at the top level") : "in " + path_));
  }
  return *e;
}

bool Map::has(std::string_view key) const { return find(key) != nullptr; }

YAML::Mark Map::value_mark(std::string_view key) const {
  const Entry& e = entry(key);
  return e.value.IsNull() ? e.key_node.Mark() : e.value.Mark();
}

YAML::Node Map::get(std::string_view key) const { return entry(key).value; }

std::string Map::label(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

double Map::number(std::string_view key, const Range& range) const {
  return read_number(*src_, entry(key).value, value_mark(key), label(key), range);
}

double Map::number_or(std::string_view key, const Range& range, double fallback) const {
  return has(key) ? number(key, range) : fallback;
}

std::int64_t Map::integer(std::string_view key, std::int64_t lo, std::int64_t hi) const {
  const Entry& e = entry(key);
  const std::string text = e.value.IsScalar() ? e.value.Scalar() : std::string();
  const std::string_view digits = strip_plus(text);
  std::int64_t value = 0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && result.ptr == digits.data() + digits.size();
  const bool too_big = result.ec == std::errc::result_out_of_range && whole;
  if (!e.value.IsScalar() || !yaml_reader::may_be_number(e.value) || !whole || (result.ec != std::errc() && !too_big)) {
    src_->fail(value_mark(key), "expected an integer for '" + label(key) + "', got " + describe(e.value));
  }
  if (too_big || value < lo || value > hi) {
    src_->fail(value_mark(key), "'" + label(key) + "' out of range: " + show(text) + " (expected " +
                                    std::to_string(lo) + " <= " + std::string(key) + " <= " + std::to_string(hi) + ")");
  }
  return value;
}

std::string Map::string(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.value.IsScalar()) {
    src_->fail(value_mark(key), "expected a string for '" + label(key) + "', got " + describe(e.value));
  }
  return e.value.Scalar();
}

Map Map::map(std::string_view key, const std::vector<std::string_view>& allowed) const {
  const Entry& e = entry(key);
  return Map(*src_, e.value, e.key_node.Mark(), label(key), allowed);
}

YAML::Node Map::list(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.value.IsSequence()) {
    src_->fail(value_mark(key), "expected a list for '" + label(key) + "', got " + describe(e.value));
  }
  return e.value;
}

}  // namespace p3at::verifier::models_detail
