// The mission content hash: a golden vector computed independently (Python's
// hashlib.blake2b(digest_size=32) over the documented byte stream), and every
// input that must change it.
#include <doctest/doctest.h>

#include <fstream>

#include "child_process.hpp"
#include "p3at/launch_gate/mission_hash.hpp"

using namespace p3at;

namespace {
const std::string kMission = "mission: {name: m}\n";
const std::string kModels = "models: {version: 1}\n";
const std::vector<verifier::Wall> kWalls{{0.0, 0.0, 10.0, 0.0}, {10.0, 0.0, 10.0, -2.5}};
}  // namespace

TEST_CASE("golden vectors: BLAKE2b-256 over the length-prefixed domain, files and walls") {
  // python3: b = hashlib.blake2b(digest_size=32); for each part: b.update(struct.pack('>Q', len(x)) + x)
  // over b"p3at-launch-gate-v1\0", mission, models; then '>Q' wall count and '>d' per coordinate.
  CHECK(gate::mission_content_hash(kMission, kModels, {}) ==
        "689c281126fdf5068fe01ba644ce3a654b5f767765eb63e47e4f826aa763bd6b");
  CHECK(gate::mission_content_hash(kMission, kModels, kWalls) ==
        "5e7c41a129e927b44308a9ee647b298e9987f3cb2f869a66e88d17725c76a02f");
  CHECK(gate::mission_content_hash("", "", {}) == "3d7f64e34a69b30ffc02823fdb1e34fd9ba50f4c29a5d51a3b7007e11249f16f");
}

TEST_CASE("any change to the mission, the models or the walls changes the hash; boundaries are unambiguous") {
  const std::string base = gate::mission_content_hash(kMission, kModels, kWalls);
  CHECK(base.size() == 64);
  CHECK(gate::mission_content_hash(kMission, kModels, kWalls) == base);  // stable
  CHECK(gate::mission_content_hash(kMission + " ", kModels, kWalls) != base);
  CHECK(gate::mission_content_hash(kMission, kModels + "#", kWalls) != base);
  auto walls = kWalls;
  walls[1].y1_m = -2.5000001;
  CHECK(gate::mission_content_hash(kMission, kModels, walls) != base);
  walls.pop_back();
  CHECK(gate::mission_content_hash(kMission, kModels, walls) != base);
  // The same bytes split differently between the two files: a different hash.
  CHECK(gate::mission_content_hash("ab", "c", {}) != gate::mission_content_hash("a", "bc", {}));
  // Swapping the files' roles: a different hash.
  CHECK(gate::mission_content_hash(kModels, kMission, kWalls) != base);
}

TEST_CASE("read_file_bytes: exact bytes, and errors that name the file") {
  const std::string path = test::scratch_path("bytes.bin");
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string("a\0b\r\n", 5);
  }
  auto bytes = gate::read_file_bytes(path);
  REQUIRE(bytes.ok());
  CHECK(bytes.value() == std::string("a\0b\r\n", 5));
  auto missing = gate::read_file_bytes(path + ".nope");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().code == Error::Code::not_found);
  CHECK(missing.error().message.find(path + ".nope") != std::string::npos);
}
