#pragma once
/// The file of a shard's part, whatever it carries: the reading and writing
/// shared by a validation campaign's part (campaign_part.hpp, docs/cluster.md)
/// and a cross-check campaign's (crosscheck/shard_part.hpp). A part is text
/// lines ending with "end<TAB>n<TAB>blake2b-256<TAB>checksum", the checksum
/// over every byte before that line, so a part cut short or changed anywhere
/// is refused as a whole before any of its numbers is believed; it is
/// written whole or not at all.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"

namespace p3at::team_sim {

/// The checksum the end line carries: BLAKE2b-256, hex, of every byte before it.
std::string part_checksum(std::string_view body);

/// The end line for `body` holding `count` records, "\n" included.
std::string part_end_line(std::string_view body, std::uint64_t count);

/// A part whose end line checks: its body (every line before the end line,
/// each ending in '\n') and the end line's count field, unparsed.
struct CheckedPart {
  std::string_view body;
  std::string_view end_count;
};

/// Refuses (invalid_argument, "source: ...") a text with no final newline or
/// no well-formed end line (cut short), or whose checksum does not match.
/// `counted` names the end line's count in messages ("runs", "missions").
Result<CheckedPart> check_part(std::string_view text, const std::string& source, std::string_view counted);

/// Writes `path` whole or not at all: `write` fills `path`.tmp, which is then
/// renamed into place, so a shard killed while writing leaves no part that
/// looks finished.
Status write_file_whole(const std::string& path, const std::function<void(std::ostream&)>& write);


/// A part's lines in order, numbered from 1 for messages.
class PartLines {
 public:
  PartLines(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  bool at_end() const { return pos_ >= text_.size(); }
  /// How many lines the text has (its '\n's; the body of a CheckedPart ends with one).
  std::size_t count() const;
  /// The next line, without its '\n'.
  std::string_view next_line();
  /// The next line's tab-separated fields.
  std::vector<std::string_view> next();
  /// The number of the line last read (0 before any).
  std::size_t line() const { return line_; }
  /// invalid_argument, "source:line: what", at the line last read.
  Error error(const std::string& what) const;

 private:
  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

/// A field for a message: quoted, cut after 40 characters, control bytes as '?'.
std::string shown(std::string_view field);

/// The next line, which must be `key` followed by exactly `values` fields
/// (any number when values < 0); returns the fields after the key.
Result<std::vector<std::string_view>> expect_line(PartLines& lines, std::string_view key, int values);

}  // namespace p3at::team_sim
