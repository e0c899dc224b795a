// Each trigger on its own (docs/executive.md).

#include <doctest/doctest.h>

#include <numbers>

#include "fake_team_link.hpp"
#include "p3at/executive/triggers.hpp"

using p3at::exec::MessageBook;
using p3at::exec::TriggerInputs;
using p3at::exec::trigger_holds;
namespace mission = p3at::mission;

TEST_CASE("AtGoal: within the radius of the goal, from the believed pose") {
  const mission::TriggerParams t = mission::AtGoalParams{{10.0, 5.0}, 0.3};
  TriggerInputs in;
  in.pose = {9.75, 5.1, 0.0};  // 0.269 m away
  CHECK(trigger_holds(t, std::nullopt, in));
  const mission::TriggerParams quarter = mission::AtGoalParams{{10.0, 5.0}, 0.25};
  in.pose = {9.75, 5.0, 0.0};  // exactly on the radius (exact in binary)
  CHECK(trigger_holds(quarter, std::nullopt, in));
  in.pose = {9.6, 5.0, 0.0};
  CHECK_FALSE(trigger_holds(t, std::nullopt, in));
}

TEST_CASE("HasTurned: accumulated turn reaches angle minus offset") {
  const double deg = std::numbers::pi / 180.0;
  TriggerInputs in;
  const mission::TriggerParams plain = mission::HasTurnedParams{90.0, 0.0};
  in.turned_rad = 89.9 * deg;
  CHECK_FALSE(trigger_holds(plain, std::nullopt, in));
  in.turned_rad = 90.0 * deg;
  CHECK(trigger_holds(plain, std::nullopt, in));
  const mission::TriggerParams offset = mission::HasTurnedParams{90.0, 5.0};
  in.turned_rad = 85.5 * deg;
  CHECK(trigger_holds(offset, std::nullopt, in));
  in.turned_rad = 84.5 * deg;
  CHECK_FALSE(trigger_holds(offset, std::nullopt, in));
}

TEST_CASE("Notified: once the message has been received") {
  MessageBook book(2);
  TriggerInputs in;
  in.messages = &book;
  const mission::TriggerParams t = mission::NotifiedParams{"go"};
  CHECK_FALSE(trigger_holds(t, 1, in));
  CHECK(book.mark_received(1));
  CHECK_FALSE(book.mark_received(1));  // not new the second time
  CHECK_FALSE(book.mark_received(9));  // out of range
  CHECK(trigger_holds(t, 1, in));
  CHECK_FALSE(trigger_holds(t, 0, in));            // a different message
  CHECK_FALSE(trigger_holds(t, std::nullopt, in));  // unknown message
}

TEST_CASE("MessageSent: only after this robot sent it and it was acknowledged") {
  MessageBook book(1);
  p3at::test::FakeTeamLink link("robot1");
  TriggerInputs in;
  in.messages = &book;
  in.team_link = &link;
  const mission::TriggerParams t = mission::MessageSentParams{"done"};
  CHECK_FALSE(trigger_holds(t, 0, in));  // never sent
  const auto seq = link.notify("done", {"robot2"});
  REQUIRE(seq.ok());
  book.record_sent(0, *seq);
  CHECK(book.last_sent(0) == *seq);
  CHECK_FALSE(trigger_holds(t, 0, in));  // sent, not acknowledged
  link.ack(*seq, "robot2");
  CHECK(trigger_holds(t, 0, in));
  CHECK_FALSE(book.last_sent(5).has_value());
}
