// The anti-replay window: fresh, duplicate, reordered, too old, big jumps.
#include <doctest/doctest.h>

#include "p3at/team_link/replay_window.hpp"

using p3at::hal::ReplayWindow;
using V = ReplayWindow::Verdict;

TEST_CASE("the first sequence number is fresh whatever it is; repeats are duplicates") {
  ReplayWindow w;
  CHECK(w.check(1700000000000000) == V::fresh);
  CHECK(w.accept(1700000000000000) == V::fresh);
  CHECK(w.highest() == 1700000000000000);
  CHECK(w.accept(1700000000000000) == V::duplicate);
  CHECK(w.check(1700000000000000) == V::duplicate);
}

TEST_CASE("reordered sequence numbers inside the window are accepted once each") {
  ReplayWindow w;
  CHECK(w.accept(100) == V::fresh);
  CHECK(w.accept(103) == V::fresh);
  CHECK(w.accept(101) == V::fresh);  // arrived late: still delivered
  CHECK(w.accept(102) == V::fresh);
  for (std::uint64_t s = 100; s <= 103; ++s) CHECK(w.accept(s) == V::duplicate);
  CHECK(w.highest() == 103);
}

TEST_CASE("below the window is too old; the edge is exact") {
  ReplayWindow w;
  REQUIRE(w.accept(1000) == V::fresh);
  CHECK(w.check(1000 - ReplayWindow::kSize + 1) == V::fresh);
  CHECK(w.check(1000 - ReplayWindow::kSize) == V::too_old);
  CHECK(w.accept(1000 - ReplayWindow::kSize) == V::too_old);
  CHECK(w.check(0) == V::too_old);
}

TEST_CASE("jumps forward keep what is still inside the window and forget the rest") {
  ReplayWindow w;
  REQUIRE(w.accept(10) == V::fresh);
  REQUIRE(w.accept(20) == V::fresh);
  REQUIRE(w.accept(10 + ReplayWindow::kSize - 1) == V::fresh);
  CHECK(w.check(10) == V::duplicate);  // exactly at the window's far edge
  REQUIRE(w.accept(10 + ReplayWindow::kSize) == V::fresh);
  CHECK(w.check(10) == V::too_old);    // slid out
  CHECK(w.check(20) == V::duplicate);  // still inside
  CHECK(w.check(15) == V::fresh);      // never seen, inside
  REQUIRE(w.accept(1'000'000) == V::fresh);  // a far jump (a restarted sender) clears the window
  CHECK(w.check(1'000'000 - 1) == V::fresh);
  CHECK(w.check(20) == V::too_old);
  CHECK(w.check(10 + ReplayWindow::kSize) == V::too_old);
}
