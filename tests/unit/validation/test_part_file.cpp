// The checksummed part file every shard's part is (team_sim/part_file.hpp):
// shared by validation and cross-check parts, so tested once here.
#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "p3at/common/file_bytes.hpp"
#include "p3at/team_sim/part_file.hpp"
#include "scratch.hpp"

using namespace p3at::team_sim;

TEST_CASE("check_part: the body back when the end line checks; cut or changed text refused") {
  const std::string body = "magic\t1\nkey\ta\tb\n";
  const std::string text = body + part_end_line(body, 7);
  CHECK(text.substr(body.size(), 8) == "end\t7\tbl");
  const auto ok = check_part(text, "p.part", "runs");
  REQUIRE(ok);
  CHECK(ok->body == body);
  CHECK(ok->end_count == "7");

  const auto error_of = [](const std::string& t) {
    const auto r = check_part(t, "p.part", "runs");
    return r ? std::string() : r.error().message;
  };
  CHECK(error_of("") == "p.part: not a complete part (no final line: cut short while it was written or copied?)");
  CHECK(error_of(text.substr(0, text.size() - 1)).find("p.part: not a complete part") == 0);
  CHECK(error_of(body + "end\t7\n") ==
        "p.part: not a complete part: the last line should be 'end <runs> blake2b-256 <checksum>', got 'end?7' "
        "(cut short while it was written or copied?)");
  std::string changed = text;
  changed[2] = 'X';
  CHECK(error_of(changed).find("p.part: checksum mismatch") == 0);
}

TEST_CASE("PartLines numbers lines; expect_line checks the key and the number of values") {
  PartLines lines("a\t1\t2\nb\t3\nc\n", "p.part");
  CHECK(lines.count() == 3);
  const auto a = expect_line(lines, "a", 2);
  REQUIRE(a);
  CHECK((*a)[1] == "2");
  const auto b = expect_line(lines, "b", 2);
  REQUIRE_FALSE(b);
  CHECK(b.error().message == "p.part:2: 'b': expected 2 value(s), got 1");
  const auto c = expect_line(lines, "x", -1);
  REQUIRE_FALSE(c);
  CHECK(c.error().message == "p.part:3: expected 'x', got 'c'");
  const auto end = expect_line(lines, "d", 0);
  REQUIRE_FALSE(end);
  CHECK(end.error().message == "p.part:3: expected 'd', got the end of the file");
}

TEST_CASE("write_file_whole, then read_file_bytes: the bytes back; a missing file is not_found") {
  const std::string path = p3at::test::scratch_path("whole.part");
  REQUIRE(write_file_whole(path, [](std::ostream& out) { out << "one\ntwo\n"; }));
  const auto text = p3at::read_file_bytes(path);
  REQUIRE(text);
  CHECK(*text == "one\ntwo\n");
  CHECK_FALSE(std::ifstream(path + ".tmp").good());  // renamed into place, no temporary left
  std::remove(path.c_str());
  const auto missing = p3at::read_file_bytes(path);
  REQUIRE_FALSE(missing);
  CHECK(missing.error().code == p3at::Error::Code::not_found);
  CHECK(missing.error().message.find(path + ": cannot open") == 0);
}
