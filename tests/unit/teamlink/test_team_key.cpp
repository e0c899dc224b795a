// The team key file: parsing, clear errors naming the file, generation, 0600 writes.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "p3at/team_link/team_key.hpp"
#include "scratch.hpp"

using namespace p3at;
using hal::TeamKey;

namespace {

using p3at::test::scratch_path;

/// Writes a key file readable by its owner only (as a key file must be).
void write_text(const std::string& path, const std::string& text) {
  {
    std::ofstream out(path, std::ios::binary);
    out << text;
  }
  ::chmod(path.c_str(), 0600);
}

const std::string kHex = "000102030405060708090a0b0c0d0e0f101112131415161718191A1B1C1D1E1F";

}  // namespace

TEST_CASE("a 64-hex-character key parses, whitespace around it ignored, either case") {
  auto key = hal::parse_team_key("  \n" + kHex + "\r\n\t", "k.key");
  REQUIRE(key.ok());
  for (std::size_t i = 0; i < TeamKey::kBytes; ++i) CHECK(key->bytes()[i] == i);
  CHECK(hal::team_key_hex(key.value()) == "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f");
}

TEST_CASE("short, long and non-hex keys are errors naming the file and the problem") {
  auto short_key = hal::parse_team_key(kHex.substr(0, 62), "/etc/p3at/team.key");
  REQUIRE_FALSE(short_key.ok());
  CHECK(short_key.error().code == Error::Code::invalid_argument);
  CHECK(short_key.error().message.find("/etc/p3at/team.key") != std::string::npos);
  CHECK(short_key.error().message.find("found 62") != std::string::npos);

  auto long_key = hal::parse_team_key(kHex + "00", "k");
  REQUIRE_FALSE(long_key.ok());
  CHECK(long_key.error().message.find("found 66") != std::string::npos);

  std::string bad = kHex;
  bad[9] = 'g';
  auto non_hex = hal::parse_team_key(bad, "k.key");
  REQUIRE_FALSE(non_hex.ok());
  CHECK(non_hex.error().message.find("character 10 is not hexadecimal") != std::string::npos);

  std::string inner_space = kHex;
  inner_space[30] = ' ';
  CHECK_FALSE(hal::parse_team_key(inner_space, "k").ok());
  CHECK_FALSE(hal::parse_team_key("", "k").ok());
}

TEST_CASE("load_team_key: missing file is not_found naming it; a good file loads") {
  const std::string missing = scratch_path("missing.key");
  auto none = hal::load_team_key(missing);
  REQUIRE_FALSE(none.ok());
  CHECK(none.error().code == Error::Code::not_found);
  CHECK(none.error().message.find(missing) != std::string::npos);

  const std::string path = scratch_path("good.key");
  write_text(path, kHex + "\n");
  auto key = hal::load_team_key(path);
  REQUIRE(key.ok());
  CHECK(key->bytes()[31] == 0x1f);

  write_text(path, "abc\n");
  auto short_file = hal::load_team_key(path);
  REQUIRE_FALSE(short_file.ok());
  CHECK(short_file.error().message.find(path) != std::string::npos);

  write_text(path, std::string(10000, 'a'));
  auto huge = hal::load_team_key(path);
  REQUIRE_FALSE(huge.ok());
  CHECK(huge.error().message.find("not a key file") != std::string::npos);
  ::unlink(path.c_str());
}

TEST_CASE("key files: only a regular file readable by its owner only, never all zeros; a FIFO does not block") {
  const std::string path = scratch_path("strict.key");
  write_text(path, kHex + "\n");
  REQUIRE(hal::load_team_key(path).ok());
  for (const ::mode_t mode : {0640u, 0604u, 0660u, 0644u}) {
    ::chmod(path.c_str(), mode);
    auto open_key = hal::load_team_key(path);
    REQUIRE_FALSE(open_key.ok());
    CHECK(open_key.error().message.find("readable by its owner only (chmod 600") != std::string::npos);
  }
  write_text(path, std::string(64, '0') + "\n");
  auto zero = hal::load_team_key(path);
  REQUIRE_FALSE(zero.ok());
  CHECK(zero.error().message.find("all zeros") != std::string::npos);
  CHECK_FALSE(hal::parse_team_key(std::string(64, '0'), "k").ok());
  ::unlink(path.c_str());

  // A FIFO with no writer: refused at once (it used to block for ever).
  const std::string fifo = scratch_path("fifo.key");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  auto from_fifo = hal::load_team_key(fifo);
  REQUIRE_FALSE(from_fifo.ok());
  CHECK(from_fifo.error().message.find("is a FIFO, not a regular file") != std::string::npos);
  // Nor does writing a key over it (--force) wait for a reader.
  auto fresh = hal::generate_team_key();
  REQUIRE(fresh.ok());
  auto over_fifo = hal::write_team_key_file(fifo, fresh.value(), true);
  REQUIRE_FALSE(over_fifo.ok());
  CHECK(over_fifo.error().message.find("FIFO") != std::string::npos);
  ::unlink(fifo.c_str());
  auto dir = hal::load_team_key("/tmp");
  REQUIRE_FALSE(dir.ok());
  CHECK(dir.error().message.find("is a directory") != std::string::npos);
}

TEST_CASE("generated keys differ, are written with mode 0600 and read back; no silent replacement") {
  auto a = hal::generate_team_key();
  auto b = hal::generate_team_key();
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a->bytes() != b->bytes());
  CHECK(hal::team_key_fingerprint(a.value()) != hal::team_key_fingerprint(b.value()));
  CHECK(hal::team_key_fingerprint(a.value()).size() == 16);
  CHECK(hal::team_key_fingerprint(a.value()) == hal::team_key_fingerprint(TeamKey(a->bytes())));

  const std::string path = scratch_path("new.key");
  REQUIRE(hal::write_team_key_file(path, a.value(), false).ok());
  struct stat st {};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  auto back = hal::load_team_key(path);
  REQUIRE(back.ok());
  CHECK(back->bytes() == a->bytes());

  auto again = hal::write_team_key_file(path, b.value(), false);
  REQUIRE_FALSE(again.ok());
  CHECK(again.error().code == Error::Code::refused);
  CHECK(again.error().message.find("already exists") != std::string::npos);
  CHECK(hal::load_team_key(path)->bytes() == a->bytes());

  ::chmod(path.c_str(), 0644);
  REQUIRE(hal::write_team_key_file(path, b.value(), true).ok());
  REQUIRE(::stat(path.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  CHECK(hal::load_team_key(path)->bytes() == b->bytes());
  ::unlink(path.c_str());

  auto no_dir = hal::write_team_key_file("/nonexistent-dir/x.key", a.value(), false);
  REQUIRE_FALSE(no_dir.ok());
  CHECK(no_dir.error().message.find("/nonexistent-dir/x.key") != std::string::npos);
}
