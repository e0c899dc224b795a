// libFuzzer target for the partial-result reader of sharded validation
// (team_sim/campaign_part.hpp, docs/cluster.md): any input either parses or
// is refused with a message naming the file (never a crash); what parses is
// written back to text that reads back and writes to the same bytes (a
// number may be written shorter than it was read: "10.0" comes back "10"). Each input is tried twice: as it is (the
// checksum refuses almost every mutation) and resealed with a fresh checksum
// line, so the line parser behind the checksum is fuzzed too.
// Seeds: tests/fuzz/corpus/campaign_part (parts of small relay campaigns).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>

#include "p3at/team_sim/campaign_part.hpp"

namespace {

void check(std::string_view text) {
  auto part = p3at::team_sim::parse_part(text, "fuzz.part");
  if (!part.ok()) {
    if (part.error().message.rfind("fuzz.part", 0) != 0) std::abort();  // the file is named first
    return;
  }
  std::ostringstream out;
  p3at::team_sim::write_part(out, *part);
  auto again = p3at::team_sim::parse_part(out.str(), "fuzz.part");
  if (!again.ok()) std::abort();  // what is written reads back
  std::ostringstream out_again;
  p3at::team_sim::write_part(out_again, *again);
  if (out_again.str() != out.str()) std::abort();  // ... to the same part, bit for bit
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check(text);
  // Resealed: cut at the last "end\t" line if any, count the run lines, and
  // close the body with its own checksum.
  const std::size_t end = text.rfind("end\t");
  const std::string body(end == std::string_view::npos ? text : text.substr(0, end));
  if (!body.empty() && body.back() != '\n') return 0;
  std::size_t runs = 0;
  for (std::size_t at = 0; (at = body.find("run\t", at)) != std::string::npos; at += 4) {
    if (at == 0 || body[at - 1] == '\n') ++runs;
  }
  check(body + "end\t" + std::to_string(runs) + "\tblake2b-256\t" + p3at::team_sim::part_checksum(body) + "\n");
  return 0;
}
