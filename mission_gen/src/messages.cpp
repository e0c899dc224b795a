// The team's messages: a robot waiting for a teammate, a robot recalled in
// the middle of a leg or a spin (the Notified racing the AtGoal or the
// HasTurned), a patrol left when a teammate says so, several recipients.
//
// No deadlock by construction: a robot waits (in a Stop, or in a patrol that
// only a message ends) only for robots earlier in a random order, and a
// recall never skips a Notify state, so every awaited message is sent.

#include <algorithm>
#include <cmath>

#include "gen_internal.hpp"

namespace p3at::mission_gen {
namespace {

// Indices of the robot's go ops.
std::vector<std::size_t> go_indices(const RobotPlan& r) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < r.ops.size(); ++i) {
    if (r.ops[i].kind == Op::Kind::go) out.push_back(i);
  }
  return out;
}

// Inserts `op` at `at`, keeping the recall targets of later ops pointing at the same ops.
void insert_op(RobotPlan& r, std::size_t at, Op op) {
  for (Op& o : r.ops) {
    if (o.recall_target >= static_cast<int>(at)) ++o.recall_target;
  }
  r.ops.insert(r.ops.begin() + static_cast<std::ptrdiff_t>(at), std::move(op));
}

// The sender's Notify, after one of its legs.
void add_notify(GenRng& rng, RobotPlan& sender, const std::string& message) {
  const std::vector<std::size_t> gos = go_indices(sender);
  const std::size_t after = gos[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(gos.size()) - 1))];
  Op op;
  op.kind = Op::Kind::notify;
  op.message = message;
  insert_op(sender, after + 1, op);
}

bool earlier(const TeamPlan& team, std::size_t a, std::size_t b) {
  const auto pa = std::find(team.order.begin(), team.order.end(), a);
  const auto pb = std::find(team.order.begin(), team.order.end(), b);
  return pa < pb;
}

// A wait for `message`: at the very start (held until a teammate is ready) or before a leg.
void add_wait(GenRng& rng, RobotPlan& r, const std::string& message) {
  Op op;
  op.kind = Op::Kind::wait;
  op.message = message;
  std::size_t at = 0;
  if (rng.chance(0.5)) {
    const std::vector<std::size_t> gos = go_indices(r);
    at = gos[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(gos.size()) - 1))];
  }
  insert_op(r, at, op);
}

// A recall on one of the robot's legs or spins that has none yet.
bool add_recall(GenRng& rng, RobotPlan& r, const std::string& message) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < r.ops.size(); ++i) {
    const Op& o = r.ops[i];
    if ((o.kind == Op::Kind::go || o.kind == Op::Kind::spin) && o.recall.empty()) candidates.push_back(i);
  }
  if (candidates.empty()) return false;
  Op& o = r.ops[rng.pick(candidates)];
  o.recall = message;
  o.recall_first = rng.chance(0.5);
  return true;
}

// A patrol between two corners before the robot's last leg, left on
// `message`; every leg it adds (there, the lap, and on to the last goal from
// either corner) is 1-25 m. No patrol when none fits (the message is then
// sent to a robot that ignores it, which the format allows).
void add_patrol(GenRng& rng, RobotPlan& r, const std::string& message, bool corridor) {
  const std::vector<std::size_t> gos = go_indices(r);
  const std::size_t last = gos.back();
  Point2 from = r.start;
  for (std::size_t i = 0; i < last; ++i) {
    if (r.ops[i].kind == Op::Kind::go) from = r.ops[i].goal;
  }
  const Point2 to = r.ops[last].goal;
  const auto fits = [](double d) { return d >= 1.0 && d <= 25.0; };
  for (int attempt = 0; attempt < 12; ++attempt) {
    Op op;
    op.kind = Op::Kind::patrol;
    op.message = message;
    // Across the last leg's direction (in a hallway: along it, either way).
    const double h = corridor ? (rng.chance(0.5) ? 0.0 : 3.141592653589793)
                              : std::atan2(to.y_m - from.y_m, to.x_m - from.x_m) + (rng.chance(0.5) ? 1.2 : -1.2);
    const double lap = rng.uniform(3.0, 10.0);
    op.goal = Point2{round_to(from.x_m + 1.5 * std::cos(h), 0.1), round_to(from.y_m + 1.5 * std::sin(h), 0.1)};
    op.goal2 = Point2{round_to(op.goal.x_m + lap * std::cos(h), 0.1), round_to(op.goal.y_m + lap * std::sin(h), 0.1)};
    if (!fits(dist(op.goal, to)) || !fits(dist(op.goal2, to))) continue;
    op.go_params = r.ops[last].go_params;
    op.radius_m = r.ops[last].radius_m;
    op.exit_first = rng.chance(0.5);
    insert_op(r, last, op);
    return;
  }
}

// Where each recall jumps: the next step, the last leg, or the end, never
// past a Notify (a teammate may be waiting for it).
void resolve_recalls(GenRng& rng, RobotPlan& r) {
  const std::vector<std::size_t> gos = go_indices(r);
  const std::size_t last_go = gos.back();
  const auto notify_between = [&r](std::size_t from, std::size_t to) {
    for (std::size_t j = from; j < to && j < r.ops.size(); ++j) {
      if (r.ops[j].kind == Op::Kind::notify) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < r.ops.size(); ++i) {
    Op& o = r.ops[i];
    if (o.recall.empty()) continue;
    std::vector<int> targets{static_cast<int>(i + 1)};
    if (i < last_go && !notify_between(i + 1, last_go)) targets.push_back(static_cast<int>(last_go));
    if (i >= last_go && !notify_between(i + 1, r.ops.size())) targets.push_back(static_cast<int>(r.ops.size()));
    o.recall_target = rng.pick(targets);
  }
}

}  // namespace

void draw_messages(GenRng& rng, TeamPlan& team) {
  const std::size_t n = team.robots.size();
  team.order.resize(n);
  for (std::size_t i = 0; i < n; ++i) team.order[i] = i;
  for (std::size_t i = n; i > 1; --i) {
    std::swap(team.order[i - 1], team.order[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(i) - 1))]);
  }
  if (n < 2) return;
  std::size_t counter = 0;
  const auto new_message = [&](std::size_t from, std::size_t to, const char* what) -> MessagePlan& {
    MessagePlan m;
    m.name = "r" + std::to_string(from + 1) + "_" + what + "_" + std::to_string(++counter);
    m.from = from;
    m.to = {to};
    add_notify(rng, team.robots[from], m.name);
    team.messages.push_back(m);
    return team.messages.back();
  };
  // Other recipients of the same message: each waits for it, is recalled by it, or ignores it.
  const auto more_recipients = [&](MessagePlan& m) {
    if (n < 3 || !rng.chance(0.3)) return;
    for (std::size_t l = 0; l < n; ++l) {
      if (l == m.from || std::find(m.to.begin(), m.to.end(), l) != m.to.end() || !rng.chance(0.6)) continue;
      m.to.push_back(l);
      const double use = rng.unit();
      if (use < 0.35 && earlier(team, m.from, l)) {
        add_wait(rng, team.robots[l], m.name);
      } else if (use < 0.7) {
        add_recall(rng, team.robots[l], m.name);
      }
    }
  };
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t k = team.order[p];
    if (p > 0 && rng.chance(0.45)) {
      const std::size_t j = team.order[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(p) - 1))];
      MessagePlan& m = new_message(j, k, "ready");
      add_wait(rng, team.robots[k], m.name);
      more_recipients(m);
    }
    if (rng.chance(0.35)) {
      std::size_t j = static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(n) - 2));
      if (j >= k) ++j;
      MessagePlan& m = new_message(j, k, "recall");
      add_recall(rng, team.robots[k], m.name);
      more_recipients(m);
    }
    if (p > 0 && rng.chance(0.25)) {
      const std::size_t j = team.order[static_cast<std::size_t>(rng.integer(0, static_cast<std::int64_t>(p) - 1))];
      MessagePlan& m = new_message(j, k, "relieve");
      add_patrol(rng, team.robots[k], m.name, team.corridor);
      more_recipients(m);
    }
  }
  for (RobotPlan& r : team.robots) resolve_recalls(rng, r);
  // Messages are listed by sender then creation, as a person groups them.
  std::stable_sort(team.messages.begin(), team.messages.end(),
                   [](const MessagePlan& a, const MessagePlan& b) { return a.from < b.from; });
}

}  // namespace p3at::mission_gen
