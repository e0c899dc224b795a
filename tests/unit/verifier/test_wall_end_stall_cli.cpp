// The body against the walls, against the runs (engine/body_contact.hpp;
// data/wall_end_stall: generated gen_7462 to its leg4). The leg's true path
// heads straight at a free-standing wall's east end, and every run of the
// simulator stalls there, nose against it, for the rest of its 900 s. The
// verifier, which had no body, drove its paths through the wall's end:
// P(t <= 165 s) 1.000 against the runs' 0.000, and with leg4's slow-down
// shortened (mission_vouched.yaml) a GO the model vouched for. With the wall moved 0.7 m
// south the runs pass it, and so must verify, to the same answer it gave
// before the body was modelled.
// `vipars verify` against 300 `vipars validate` runs each (about 4 s each in release).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_json.hpp"
#include "cli_run.hpp"

namespace {

using p3at::test::run_json;

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/wall_end_stall/" + name;
}

struct Both {
  nlohmann::json verified, runs;
};

Both verify_and_validate(const std::string& world, const std::string& models,
                         const std::string& mission = "mission.yaml") {
  const std::string vipars = p3at::test::vipars_binary();
  Both b;
  b.verified = run_json(vipars + " verify " + data(mission) + " --models " + data(models) + " --json");
  b.runs =
      run_json(vipars + " validate " + data(mission) + " --world " + data(world) + " --trials 300 --seed 1 --json");
  MESSAGE(mission << " in " << world << ": P(t <= Tmax) verify " << b.verified.at("p_time").get<double>() << ", 300 runs "
                << b.runs.at("p_time").get<double>() << "; verify's blocked mass "
                << b.verified.at("blocked_mass").get<double>());
  return b;
}

}  // namespace

TEST_CASE("a leg whose true path meets a wall's end stalls there, as every run does") {
  const Both b = verify_and_validate("world.yaml", "models.yaml");
  CHECK(b.runs.at("p_time").get<double>() == 0.0);
  CHECK(b.verified.at("p_time").get<double>() < 0.01);
  CHECK(b.verified.at("blocked_mass").get<double>() > 0.99);
  // Stuck on leg4, near the wall's end (7.35, 9.2) where the runs stand.
  const auto& blocked = b.verified.at("blocked");
  REQUIRE(blocked.size() >= 1);
  CHECK(blocked[0].at("state").get<std::string>() == "leg4");
  CHECK(std::hypot(blocked[0].at("x_m").get<double>() - 7.35, blocked[0].at("y_m").get<double>() - 9.2) < 1.0);
  CHECK(b.verified.at("decision").get<std::string>() == "no-go");
}

TEST_CASE("the mission with every approximation vouched for: the GO that every run refuted is a NO-GO") {
  // Before the body was modelled: decision "go", P(success) 1.000, evaluable.
  const Both b = verify_and_validate("world.yaml", "models.yaml", "mission_vouched.yaml");
  CHECK(b.verified.at("evaluable").get<bool>());
  CHECK(b.runs.at("p_joint").get<double>() == 0.0);
  CHECK(b.verified.at("p_joint").get<double>() < 0.01);
  CHECK(b.verified.at("decision").get<std::string>() == "no-go");
}

TEST_CASE("the same leg past the wall moved clear: no stall, the runs' time") {
  const Both b = verify_and_validate("world_clear.yaml", "models_clear.yaml");
  CHECK(b.runs.at("p_time").get<double>() == 1.0);
  CHECK(b.verified.at("p_time").get<double>() > 0.999);
  CHECK(b.verified.at("blocked_mass").get<double>() < 1e-9);
  // 95.80 ± 2.29 s against 300 runs' 95.79 ± 2.29 s.
  CHECK(std::abs(b.verified.at("completion_mean_s").get<double>() - b.runs.at("completion_mean_s").get<double>()) <
        0.5);
}
