#include "p3at/team_sim/part_file.hpp"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

namespace p3at::team_sim {
namespace {

Error invalid(std::string message) { return make_error(Error::Code::invalid_argument, std::move(message)); }

}  // namespace

std::string part_checksum(std::string_view body) {
  std::array<unsigned char, crypto_generichash_BYTES> digest{};
  if (sodium_init() < 0) return std::string(2 * digest.size(), '0');
  crypto_generichash(digest.data(), digest.size(), reinterpret_cast<const unsigned char*>(body.data()), body.size(),
                     nullptr, 0);
  std::array<char, 2 * crypto_generichash_BYTES + 1> text{};
  sodium_bin2hex(text.data(), text.size(), digest.data(), digest.size());
  return std::string(text.data(), 2 * digest.size());
}

std::string part_end_line(std::string_view body, std::uint64_t count) {
  return "end\t" + std::to_string(count) + "\tblake2b-256\t" + part_checksum(body) + "\n";
}

Result<CheckedPart> check_part(std::string_view text, const std::string& source, std::string_view counted) {
  if (text.empty() || text.back() != '\n') {
    return invalid(source + ": not a complete part (no final line: cut short while it was written or copied?)");
  }
  const std::size_t last = text.rfind('\n', text.size() - 2);
  const std::size_t end_start = last == std::string_view::npos ? 0 : last + 1;
  const std::string_view body = text.substr(0, end_start);
  const std::string_view end_line = text.substr(end_start, text.size() - 1 - end_start);
  PartLines end_lines(end_line, source);
  const auto ef = end_lines.next();
  if (ef.size() != 4 || ef[0] != "end" || ef[2] != "blake2b-256") {
    return invalid(source + ": not a complete part: the last line should be 'end <" + std::string(counted) +
                   "> blake2b-256 <checksum>', got " + shown(end_line) + " (cut short while it was written or copied?)");
  }
  if (ef[3] != part_checksum(body)) {
    return invalid(source + ": checksum mismatch: the part was changed or damaged after it was written; rerun its shard");
  }
  return CheckedPart{body, ef[1]};
}

Status write_file_whole(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return make_error(Error::Code::io, tmp + ": cannot write: " + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) return make_error(Error::Code::io, tmp + ": write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    return make_error(Error::Code::io, path + ": cannot rename " + tmp + " into place: " + std::strerror(err));
  }
  return {};
}


std::size_t PartLines::count() const { return static_cast<std::size_t>(std::count(text_.begin(), text_.end(), '\n')); }

std::string_view PartLines::next_line() {
  const std::size_t eol = text_.find('\n', pos_);
  const std::string_view line = text_.substr(pos_, eol == std::string_view::npos ? std::string_view::npos : eol - pos_);
  pos_ = eol == std::string_view::npos ? text_.size() : eol + 1;
  ++line_;
  return line;
}

std::vector<std::string_view> PartLines::next() {
  const std::string_view line = next_line();
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', start);
    fields.push_back(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start));
    if (tab == std::string_view::npos) break;
    start = tab + 1;
  }
  return fields;
}

Error PartLines::error(const std::string& what) const {
  return invalid(source_ + ":" + std::to_string(line_) + ": " + what);
}

std::string shown(std::string_view field) {
  constexpr std::size_t kMax = 40;
  std::string out = "'" + std::string(field.substr(0, kMax)) + (field.size() > kMax ? "...'" : "'");
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f) c = '?';
  }
  return out;
}

Result<std::vector<std::string_view>> expect_line(PartLines& lines, std::string_view key, int values) {
  if (lines.at_end()) return lines.error("expected '" + std::string(key) + "', got the end of the file");
  auto fields = lines.next();
  if (fields[0] != key) return lines.error("expected '" + std::string(key) + "', got " + shown(fields[0]));
  if (values >= 0 && fields.size() != static_cast<std::size_t>(values) + 1) {
    return lines.error("'" + std::string(key) + "': expected " + std::to_string(values) + " value(s), got " +
                       std::to_string(fields.size() - 1));
  }
  fields.erase(fields.begin());
  return fields;
}

}  // namespace p3at::team_sim
