// In-mission re-verification: the worker (newest request wins, errors and
// exceptions become answers), and the monitor on a real RobotExecutive with
// fake hardware: a re-verification at each transition from where the team
// is, the new probability published in status, and the mission's abort
// action below the abort threshold.
#include <doctest/doctest.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <stdexcept>

#include "fake_clock.hpp"
#include "fake_drive_base.hpp"
#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/launch_gate/gate_team_link.hpp"
#include "p3at/launch_gate/in_mission_monitor.hpp"
#include "p3at/launch_gate/reverifier.hpp"

using namespace p3at;

namespace {

verifier::TeamSnapshot at(double t_s) {
  verifier::TeamSnapshot s;
  s.elapsed_s = t_s;
  return s;
}

/// robot1 of the relay on fake hardware, its team link wrapped for the gate,
/// robot2's link connected (it acknowledges when polled).
struct Rig {
  mission::Mission mission = test::relay_mission();
  test::FakeClock clock{0};
  test::FakeDriveBase drive{&clock};
  test::FakeTeamLink inner{"robot1"};
  test::FakeTeamLink peer{"robot2"};
  gate::GateTeamLink link{inner, clock};
  test::ScriptedVerifier scripted;
  std::optional<gate::Reverifier> reverifier;
  std::optional<gate::InMissionMonitor> monitor;
  std::optional<exec::RobotExecutive> executive;
  std::vector<std::string> abort_reasons;

  explicit Rig(double p_joint, double abort_threshold = 0.0,
               mission::AbortAction action = mission::AbortAction::continue_and_warn) {
    test::FakeTeamLink::connect(inner, peer);
    mission.criteria.abort_threshold = abort_threshold;
    mission.criteria.abort_action = action;
    scripted.p_joint = p_joint;
    reverifier.emplace(mission, verifier::Models{}, verifier::VerifyOptions{}, std::vector<std::string>{},
                       scripted.source());
    monitor.emplace(mission, 0, mission.criteria, *reverifier, link);
    exec::ExecutiveOptions options;
    options.p_success = 0.95;
    options.on_transition = [this](const exec::TransitionEvent& e) { monitor->on_transition(e); };
    executive.emplace(mission, 0, drive, link, clock, options);
    monitor->attach(*executive);
    link.after_poll = [this] {
      if (auto reason = monitor->on_poll()) abort_reasons.push_back(*reason);
    };
  }

  void cycle() {
    (void)drive.wait_for_update(100);
    executive->cycle();
    std::vector<hal::TeamNotification> got;
    (void)peer.poll(clock.now_us(), got);
  }
  /// Cycles until the executive leaves `state` (at most `limit` cycles).
  void run_while_in(const std::string& state, int limit = 400) {
    for (int i = 0; i < limit && executive->running() && executive->state_name() == state; ++i) cycle();
  }
};

}  // namespace

TEST_CASE("Reverifier: the newest request replaces one not yet started; answers come back in order") {
  std::mutex gate_mutex;
  std::condition_variable opened;
  bool open = false;
  bool entered = false;
  int calls = 0;
  gate::VerdictSource blocking = [&](const mission::Mission&, const verifier::Models&, const verifier::VerifyOptions&,
                                     const std::vector<std::string>&,
                                     const verifier::TeamSnapshot* from) -> Result<verifier::VerifyResult> {
    std::unique_lock lock(gate_mutex);
    entered = true;
    opened.notify_all();
    opened.wait(lock, [&] { return open; });
    ++calls;
    verifier::VerifyResult r;
    r.p_joint = from != nullptr ? from->elapsed_s / 100.0 : -1.0;
    return r;
  };
  gate::Reverifier rv(test::relay_mission(), verifier::Models{}, {}, {}, blocking);
  CHECK(rv.request(at(10.0), "first") == 1);
  {
    // Once the worker is inside the first job, two more: the middle one is dropped.
    std::unique_lock lock(gate_mutex);
    opened.wait(lock, [&] { return entered; });
  }
  CHECK(rv.request(at(20.0), "second") == 2);
  CHECK(rv.request(at(30.0), "third") == 3);
  {
    std::lock_guard lock(gate_mutex);
    open = true;
  }
  opened.notify_all();
  rv.drain();
  const auto answers = rv.take();
  REQUIRE(answers.size() == 2);
  CHECK(answers[0].id == 1);
  CHECK(answers[0].cause == "first");
  CHECK(answers[0].result->p_joint == doctest::Approx(0.10));
  CHECK(answers[1].id == 3);
  CHECK(answers[1].at_s == doctest::Approx(30.0));
  CHECK(answers[1].result->p_joint == doctest::Approx(0.30));
  CHECK(rv.dropped() == 1);
  CHECK(calls == 2);
  CHECK(rv.take().empty());
}

TEST_CASE("Reverifier: a verifier error or exception comes back as an error answer") {
  test::ScriptedVerifier scripted;
  scripted.error = make_error(Error::Code::invalid_argument, "no model for robot9");
  gate::Reverifier rv(test::relay_mission(), verifier::Models{}, {}, {}, scripted.source());
  rv.request(at(1.0), "x");
  rv.drain();
  auto answers = rv.take();
  REQUIRE(answers.size() == 1);
  REQUIRE_FALSE(answers[0].result.ok());
  CHECK(answers[0].result.error().message == "no model for robot9");

  gate::Reverifier throwing(test::relay_mission(), verifier::Models{}, {}, {},
                            [](const mission::Mission&, const verifier::Models&, const verifier::VerifyOptions&,
                               const std::vector<std::string>&,
                               const verifier::TeamSnapshot*) -> Result<verifier::VerifyResult> {
                              throw std::runtime_error("boom");
                            });
  throwing.request(at(1.0), "y");
  throwing.drain();
  answers = throwing.take();
  REQUIRE(answers.size() == 1);
  REQUIRE_FALSE(answers[0].result.ok());
  CHECK(answers[0].result.error().message.find("boom") != std::string::npos);
}

TEST_CASE("monitor: one re-verification per transition, from where the team is; the new probability is published") {
  Rig rig(0.87);
  rig.run_while_in("drive");
  REQUIRE(rig.executive->state_name() == "tell");
  rig.reverifier->drain();
  REQUIRE(rig.scripted.calls.size() == 1);
  const verifier::TeamSnapshot& s1 = *rig.scripted.calls[0].snapshot;
  CHECK(s1.robots[0].state == 1);  // the state just entered
  CHECK(s1.elapsed_s == doctest::Approx(rig.executive->elapsed_s()));
  CHECK(s1.robots[0].entered_s == doctest::Approx(s1.elapsed_s));
  CHECK(s1.robots[0].travelled_m == doctest::Approx(std::hypot(rig.executive->pose().x_m - 1.0,
                                                               rig.executive->pose().y_m - 1.0)).epsilon(0.05));
  CHECK(s1.robots[0].x_m == doctest::Approx(rig.executive->pose().x_m));
  CHECK_FALSE(s1.messages_sent[0]);  // the Notify state sends on entry, after the snapshot
  CHECK(s1.robots[1].state == 0);    // robot2 not heard: still waiting at its start

  rig.cycle();  // the answer is picked up on the next poll, and published
  CHECK(rig.monitor->answers() == 1);
  CHECK(rig.monitor->latest_p() == doctest::Approx(0.87));
  CHECK(rig.inner.status_sent.back().p_success == doctest::Approx(0.87));

  rig.run_while_in("tell");
  CHECK(rig.executive->outcome().phase == exec::Phase::finished);
  rig.reverifier->drain();
  REQUIRE(rig.scripted.calls.size() == 2);
  const verifier::TeamSnapshot& s2 = *rig.scripted.calls[1].snapshot;
  CHECK(s2.robots[0].state == 2);
  CHECK(s2.robots[0].finished);
  CHECK(s2.messages_sent[0]);
  CHECK(s2.messages_received[0]);  // robot2 acknowledged: that is what MessageSent waited for
  rig.cycle();
  CHECK(rig.monitor->answers() == 2);
  CHECK(rig.abort_reasons.empty());
}

TEST_CASE("monitor: below the abort threshold with stop_and_notify, the abort is asked for once") {
  Rig rig(0.30, 0.5, mission::AbortAction::stop_and_notify);
  rig.run_while_in("drive");
  rig.reverifier->drain();
  rig.cycle();
  REQUIRE(rig.abort_reasons.size() == 1);
  CHECK(rig.abort_reasons[0].find("P(success) 0.3000 < abort threshold 0.5000") != std::string::npos);
  CHECK(rig.inner.status_sent.back().p_success == doctest::Approx(0.30));
  // A second low answer does not ask again.
  rig.reverifier->request(at(9.0), "again");
  rig.reverifier->drain();
  rig.cycle();
  CHECK(rig.abort_reasons.size() == 1);
  CHECK(rig.monitor->lowest_p() == doctest::Approx(0.30));
}

TEST_CASE("monitor: below the abort threshold with continue_and_warn, the mission goes on and says so") {
  Rig rig(0.30, 0.5, mission::AbortAction::continue_and_warn);
  rig.run_while_in("drive");
  rig.reverifier->drain();
  rig.cycle();
  CHECK(rig.abort_reasons.empty());
  // The status republished with the new probability says so (while running).
  const auto warned = std::find_if(rig.inner.status_sent.begin(), rig.inner.status_sent.end(), [](const auto& s) {
    return s.phase == "running" && s.reason.find("warning: re-verification") != std::string::npos;
  });
  REQUIRE(warned != rig.inner.status_sent.end());
  CHECK(warned->p_success == doctest::Approx(0.30));
  rig.run_while_in("tell");
  CHECK(rig.executive->outcome().phase == exec::Phase::finished);
}

TEST_CASE("monitor: above the abort threshold, or with it off, nothing is done") {
  Rig off(0.10, 0.0, mission::AbortAction::stop_and_notify);
  off.run_while_in("drive");
  off.reverifier->drain();
  off.cycle();
  CHECK(off.abort_reasons.empty());
  Rig above(0.60, 0.5, mission::AbortAction::stop_and_notify);
  above.run_while_in("drive");
  above.reverifier->drain();
  above.cycle();
  CHECK(above.abort_reasons.empty());
  CHECK(above.inner.status_sent.back().reason.empty());
}
