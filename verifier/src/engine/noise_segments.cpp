#include "engine/noise_segments.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "engine/direction_arcs.hpp"
#include "engine/error_strata.hpp"

namespace p3at::verifier::engine {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Successive draws' quadrature directions are turned by the golden angle, so
// that over many redraws the directions used do not sit on one lattice.
constexpr double kGoldenAngleRad = 2.399963229728653;

// A path that has not moved over a whole window (a Spin: not turned either),
// and on which no path has finished meanwhile, is stuck (pinned by a wall's avoidance
// field, or held off its goal by NOISE where the two balance): stepping it on
// to the state's cycle cap (ten times the leg's nominal length) changes
// nothing but the cost. gen_5062's patrol and last leg took 0.8 million
// cycles per analysis, most of them on pinned paths, and the mission ran out
// of its work budget. The window is twice the simulator's "not moving for
// 10 s" diagnosis of a pinned run. Only where nothing around moves (a path
// held by a driving teammate's body goes on once the teammate has passed),
// and one path alone only when its draw of NOISE lasts to the cap: a redraw
// moves a path held off its goal (gen_5020: a draw held 40 s keeps robot1
// 0.18 m from its goal, outside AtGoal's 0.1 m, and the next draw's swing
// takes it in; checked within the draw, 0.10 blocked became 0.62). Under
// redraws the check is on the cloud between draws, and no path may have
// finished over the window: a cloud that keeps its shape while paths leave
// it through the circle is not stuck.
constexpr std::size_t kStillWindowCycles = 200;
constexpr double kStillM = 0.01;
constexpr double kStillRad = 0.5 * kPi / 180.0;
// Live mass below this (of the state's 1) is counted stuck at once; the
// sequencer treats less than 1e-9 of a branch as nothing anyway.
constexpr double kNegligibleLiveMass = 1e-10;

/// Where a path (or the cloud of live walkers) was at the last look.
struct StillCheck {
  std::size_t next = kStillWindowCycles;
  double x = 0.0, y = 0.0, theta = 0.0, finished = 0.0;
  bool armed = false;
  /// A Spin's progress is its turn; a leg's is its position (a robot pinned
  /// by a wall may keep turning on the spot: the simulator's "not moving").
  bool spin = false;
  /// True when nothing moved or finished since the last look `kStillWindowCycles` ago.
  bool still(std::size_t cycles, double px, double py, double ptheta, double finished_mass) {
    if (cycles < next) return false;
    const bool same = armed && std::hypot(px - x, py - y) < kStillM &&
                      (!spin || std::abs(ptheta - theta) < kStillRad) && finished_mass - finished < 1e-12;
    next = cycles + kStillWindowCycles;
    x = px;
    y = py;
    theta = ptheta;
    finished = finished_mass;
    armed = true;
    return same;
  }
};

/// A mean-path sample of one path (noise_quadrature's per-second sums).
struct PathSample2 {
  std::size_t index = 0;
  double x_m = 0.0, y_m = 0.0;
};

/// How one path under a draw ended: its outcome (direction_arcs.hpp), the
/// walker there, and its samples for the mean path.
struct PathEnd {
  DrawOutcome outcome = kDrawRunning;
  Walker walker;
  std::vector<PathSample2> samples;
};

// The clustering's metric: metres, with a heading difference of 1 rad
// counted as 0.3 m, a speed difference of 1 m/s as 2 m and a turn rate of
// 1 rad/s as 0.3 m (what each does to where the path goes next, roughly).
using Features = std::array<double, 5>;
Features features(const Walker& w) {
  return {w.q.x_m, w.q.y_m, 0.3 * w.q.theta_rad, 2.0 * w.q.trans_mps, 0.3 * w.q.rot_radps};
}
double distance2(const Features& a, const Features& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

using State5 = Eigen::Matrix<double, 5, 1>;
using Cov5 = Eigen::Matrix<double, 5, 5>;

/// The part of a walker the restoring map acts on: pose and velocities.
State5 state_of(const Walker& w) {
  State5 v;
  v << w.q.x_m, w.q.y_m, w.q.theta_rad, w.q.trans_mps, w.q.rot_radps;
  return v;
}

/// The weighted covariance of the walkers' state_of(), walker k's heading
/// read `turns[k]` radians (whole turns) further round.
Cov5 state_cov(const std::vector<Walker>& ws, const std::vector<double>& turns, State5& mean) {
  const auto faced = [&](std::size_t k) {
    State5 v = state_of(ws[k]);
    v(2) += turns[k];
    return v;
  };
  double total = 0.0;
  mean.setZero();
  for (std::size_t k = 0; k < ws.size(); ++k) {
    mean += ws[k].weight * faced(k);
    total += ws[k].weight;
  }
  Cov5 cov = Cov5::Zero();
  if (!(total > 0.0)) return cov;
  mean /= total;
  for (std::size_t k = 0; k < ws.size(); ++k) {
    const State5 d = faced(k) - mean;
    cov += (ws[k].weight / total) * d * d.transpose();
  }
  return cov;
}

Walker merge(const std::vector<const Walker*>& members) {
  Walker out;
  double total = 0.0;
  for (const Walker* m : members) total += m->weight;
  out.cycles = members.front()->cycles;
  out.weight = total;
  out.q = BaseState{};
  out.before = BaseState{};
  out.error = ErrorState{};
  for (const Walker* m : members) {
    const double f = m->weight / total;
    out.q.x_m += f * m->q.x_m;
    out.q.y_m += f * m->q.y_m;
    out.q.theta_rad += f * m->q.theta_rad;
    out.q.trans_mps += f * m->q.trans_mps;
    out.q.rot_radps += f * m->q.rot_radps;
    out.before.x_m += f * m->before.x_m;
    out.before.y_m += f * m->before.y_m;
    out.before.theta_rad += f * m->before.theta_rad;
    out.before.trans_mps += f * m->before.trans_mps;
    out.before.rot_radps += f * m->before.rot_radps;
    out.turned_rad += f * m->turned_rad;
    out.turned_before_rad += f * m->turned_before_rad;
    out.at_goal_jitter_var += f * m->at_goal_jitter_var;
    out.turn_jitter_var += f * m->turn_jitter_var;
    out.error.mean += f * m->error.mean;
    out.error.cov += f * m->error.cov;
  }
  // The members' error means differ mostly because their odometric poses do
  // (a scale error grows with the distance driven, a heading error with the
  // turn): that spread is the pose spread, which the merged walkers keep
  // (see the restoring scale below), and the end of the state regresses it
  // out (error_given_end). Adding it to the covariance here as well would
  // count it again at every redraw.
  return out;
}

/// The whole turns that bring `theta` within half a turn of `ref` (none when
/// it is within already).
double turns_to_face(double theta, double ref) {
  if (std::abs(theta - ref) <= kPi) return 0.0;
  return std::round((ref - theta) / (2.0 * kPi)) * 2.0 * kPi;
}

/// The way the walkers face on average (their weighted circular mean), as
/// the heading within half a turn of `near`; `near` itself when they face
/// every way equally.
double mean_facing(const std::vector<Walker>& ws, double near) {
  double c = 0.0, s = 0.0;
  for (const Walker& w : ws) {
    c += w.weight * std::cos(w.q.theta_rad);
    s += w.weight * std::sin(w.q.theta_rad);
  }
  if (!(std::hypot(c, s) > 0.0)) return near;
  const double mean = std::atan2(s, c);
  return mean + turns_to_face(mean, near);
}

}  // namespace

std::vector<Walker> reduce_walkers(const std::vector<Walker>& walkers, std::size_t keep) {
  keep = std::max<std::size_t>(keep, 1);
  if (walkers.size() <= keep) return walkers;
  const std::size_t n = walkers.size();
  std::vector<Features> f(n);
  for (std::size_t i = 0; i < n; ++i) f[i] = features(walkers[i]);

  // Seeds: the heaviest, then repeatedly the walker with the largest
  // weight × squared distance to its nearest seed (ties: lowest index).
  std::vector<Features> centres;
  std::size_t first = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (walkers[i].weight > walkers[first].weight) first = i;
  }
  centres.push_back(f[first]);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  while (centres.size() < keep) {
    std::size_t best = n;
    double best_score = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], distance2(f[i], centres.back()));
      const double score = walkers[i].weight * nearest[i];
      if (score > best_score) {
        best_score = score;
        best = i;
      }
    }
    if (best == n) break;  // every walker sits on a seed already
    centres.push_back(f[best]);
  }
  // Nearest-centre passes (Lloyd), weighted.
  std::vector<std::size_t> label(n, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < centres.size(); ++c) {
        const double d = distance2(f[i], centres[c]);
        if (d < best) {
          best = d;
          label[i] = c;
        }
      }
    }
    if (pass == 1) break;
    std::vector<Features> sum(centres.size(), Features{});
    std::vector<double> mass(centres.size(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t d = 0; d < f[i].size(); ++d) sum[label[i]][d] += walkers[i].weight * f[i][d];
      mass[label[i]] += walkers[i].weight;
    }
    for (std::size_t c = 0; c < centres.size(); ++c) {
      if (mass[c] > 0.0) {
        for (std::size_t d = 0; d < sum[c].size(); ++d) centres[c][d] = sum[c][d] / mass[c];
      }
    }
  }
  std::vector<Walker> out;
  std::vector<std::size_t> kept_as(centres.size(), n);  // centre -> its walker in out (n: none)
  for (std::size_t c = 0; c < centres.size(); ++c) {
    std::vector<const Walker*> members;
    for (std::size_t i = 0; i < n; ++i) {
      if (label[i] == c && walkers[i].weight > 0.0) members.push_back(&walkers[i]);
    }
    if (!members.empty()) {
      kept_as[c] = out.size();
      out.push_back(merge(members));
    }
  }

  // Restore the spread merging removed (the within-cluster part of the
  // children's covariance): the clusters' deviations from their mean are
  // mapped by L_in L_out^-1 (Cholesky factors, a small ridge for degenerate
  // directions), so their pose-and-velocity covariance is exactly the
  // children's. (Scaling along the children's principal axes instead, which
  // ignores the clusters' own correlations, compounded at a redraw every
  // cycle: the duration's spread came out 3x the simulator's.)
  //
  // The map reads each heading as the way the walker faces. Headings are
  // continuous per path, so a robot turned about left and one turned about
  // right face the same way with headings a whole turn apart as numbers
  // (+3.0 and -3.3 rad); read as numbers, that is a heading spread of 3 rad,
  // which the map then put into every kept walker's pose and velocities. On
  // generated gen_7365 (leg2's goal straight behind, the NOISE deciding the
  // side) every path came out 2.5 s late against the runs.
  //  - Each kept walker is brought within half a turn of the way the
  //    children face on average (their circular mean: the cut half a turn
  //    away then falls where fewest of them are; cut at the heaviest
  //    walker's heading instead, gen_7016's leg entered facing about came out
  //    0.18 off its runs' time curve rather than 0.08).
  //  - Each child is read through its own cluster's turn, so the map's two
  //    covariances differ only by the spread within clusters, as they must.
  //    Brought within half a turn one by one, a cluster lying across the cut
  //    was read as half a turn wide: the map churned the headings of a robot
  //    pinned by a wall, turning on the spot, whose cloud then took twice as
  //    long to be found standing still (tests/unit/verifier/test_stuck_paths.cpp).
  // Clustering and merging keep the numbers: walkers a turn apart are far
  // apart there and are not merged.
  const double facing = mean_facing(walkers, walkers[first].q.theta_rad);
  std::vector<double> turns_out(out.size()), turns_in(n, 0.0);
  for (std::size_t k = 0; k < out.size(); ++k) turns_out[k] = turns_to_face(out[k].q.theta_rad, facing);
  for (std::size_t i = 0; i < n; ++i) {
    if (kept_as[label[i]] < out.size()) turns_in[i] = turns_out[kept_as[label[i]]];
  }
  State5 mean_in, mean_out;
  const Cov5 cov_in = state_cov(walkers, turns_in, mean_in);
  const Cov5 cov_out = state_cov(out, turns_out, mean_out);
  const Cov5 ridge = (1e-14 + 1e-9 * cov_in.trace()) * Cov5::Identity();
  const Eigen::LLT<Cov5> l_in(cov_in + ridge);
  const Eigen::LLT<Cov5> l_out(cov_out + ridge);
  if (l_in.info() != Eigen::Success || l_out.info() != Eigen::Success) return out;
  const Cov5 lo = l_out.matrixL();
  const Cov5 map = Cov5(l_in.matrixL()) * lo.inverse();
  if (!map.allFinite()) return out;
  for (std::size_t k = 0; k < out.size(); ++k) {
    Walker& w = out[k];
    State5 d = state_of(w);
    d(2) += turns_out[k];
    d -= mean_out;
    const State5 moved = map * d - d;
    w.q.x_m += moved(0);
    w.q.y_m += moved(1);
    w.q.theta_rad += moved(2);
    w.q.trans_mps += moved(3);
    w.q.rot_radps += moved(4);
    w.before.x_m += moved(0);
    w.before.y_m += moved(1);
    w.before.theta_rad += moved(2);
  }
  return out;
}

namespace {

/// reduce_walkers() within each stratum of the entry error (engine/error_strata):
/// merging a pinned stratum with one that gets through would put their
/// average beside the wall, which neither is. The middle stratum keeps
/// `keep`, the others an eighth of it (they weigh 45 % between them, and
/// what they must tell is mostly whether they get through). One stratum
/// (no split): reduce_walkers() itself. (Made one cloud again once no walker
/// had an obstacle within reach, the strata lost what they would have told
/// at a second wall: tried, and not kept; docs/verifier.md.)
std::vector<Walker> reduce_by_stratum(const std::vector<Walker>& children, std::size_t keep) {
  const bool split = std::any_of(children.begin(), children.end(), [](const Walker& w) { return w.stratum != 0; });
  if (!split) return reduce_walkers(children, keep);
  std::vector<Walker> out;
  for (std::size_t k = 0; k < kErrorStrata; ++k) {
    std::vector<Walker> group;
    for (const Walker& w : children) {
      if (w.stratum == k) group.push_back(w);
    }
    if (group.empty()) continue;
    for (Walker& w : reduce_walkers(group, k == 0 ? keep : std::max<std::size_t>(1, keep / 8))) {
      w.stratum = static_cast<std::uint8_t>(k);
      out.push_back(std::move(w));
    }
  }
  return out;
}

}  // namespace

NoiseQuadrature noise_quadrature(const PathStepper& stepper, const Walker& start, std::int64_t persistence,
                                 std::size_t directions, std::size_t keep, std::size_t keep_near, std::size_t cap,
                                 LegTrajectory* record) {
  Walker one = start;
  one.weight = 1.0;
  return noise_quadrature(stepper, std::vector<Walker>{one}, persistence, directions, keep, keep_near, cap, record);
}

NoiseQuadrature noise_quadrature(const PathStepper& stepper, const std::vector<Walker>& starts,
                                 std::int64_t persistence, std::size_t directions, std::size_t keep,
                                 std::size_t keep_near, std::size_t cap, LegTrajectory* record) {
  NoiseQuadrature out;
  directions = std::max<std::size_t>(directions, 1);
  const std::size_t n_starts = std::max<std::size_t>(starts.size(), 1);
  // Up to one start point per direction, the first draw's directions are
  // dealt out among the start points (direction g to start g mod n): the
  // same `directions` paths, equally spaced, as from one start, so start
  // points cost nothing (Bounding Overwatch's point took 3.3 x as long with
  // every start point under every direction). Beyond that (a leg without
  // NOISE: one direction) every start point gets every direction, and so it
  // does when the directions cannot be dealt evenly: the NOISE's direction
  // does not depend on where the robot started, so each direction must carry
  // 1 / directions of the mass. Dealt among unequal start weights (a robot
  // facing about, whose few points that turn the other way weigh less,
  // entry_walkers) or unevenly (3 starts, 8 directions), the heavy starts'
  // directions outweighed the others: gen_7016's second leg, entered facing
  // about with 3 % of its start points' weight turning the other way, drew
  // four of its eight directions with 97 % of the mass and was predicted
  // 0.21 s early (tests/unit/verifier/test_turn_about_entry_cli.cpp).
  //
  // Starts split into strata of the entry error (engine/error_strata) are
  // dealt within each stratum: the strata are different robots' errors, not
  // different places, and each must see every NOISE direction. `groups`
  // holds each stratum's starts (one group when nothing is split).
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t s = 0; s < starts.size(); ++s) {
    if (groups.size() <= starts[s].stratum) groups.resize(starts[s].stratum + std::size_t{1});
    groups[starts[s].stratum].push_back(s);
  }
  std::erase_if(groups, [](const std::vector<std::size_t>& g) { return g.empty(); });
  const bool even_starts = std::all_of(groups.begin(), groups.end(), [&starts](const std::vector<std::size_t>& g) {
    const double first = starts[g.front()].weight;
    return std::all_of(g.begin(), g.end(), [&](std::size_t s) {
      return std::abs(starts[s].weight - first) <= 1e-9 * std::max(1.0, std::abs(first));
    });
  });
  const std::size_t per_group = groups.empty() ? 1 : groups.front().size();
  const bool same_groups = std::all_of(groups.begin(), groups.end(),
                                       [per_group](const std::vector<std::size_t>& g) { return g.size() == per_group; });
  const bool dealt =
      per_group > 1 && per_group <= directions && directions % per_group == 0 && even_starts && same_groups;
  const std::size_t first_paths = dealt ? groups.size() * directions : n_starts * directions;
  if (record != nullptr) {
    record->paths.assign(first_paths, {});
    record->weights.assign(first_paths, 0.0);
    record->stuck.assign(first_paths, 0);
  }
  const std::size_t every = stepper.sample_every();
  // The mean path and the paths' spread about it: sums of weight × position
  // and of its products per sample index.
  std::vector<double> sx, sy, sw, sxx, sxy, syy;
  const auto add_sample = [&](std::size_t i, double weight, double x, double y) {
    if (sx.size() <= i) {
      for (auto* v : {&sx, &sy, &sw, &sxx, &sxy, &syy}) v->resize(i + 1, 0.0);
    }
    sx[i] += weight * x;
    sy[i] += weight * y;
    sw[i] += weight;
    sxx[i] += weight * x * x;
    sxy[i] += weight * x * y;
    syy[i] += weight * y * y;
  };

  const std::size_t length = persistence > 0 ? static_cast<std::size_t>(persistence) : cap + 1;
  std::vector<Walker> live = starts;
  {
    double total = 0.0;
    for (const Walker& w : live) total += w.weight;
    for (Walker& w : live) w.weight = total > 0.0 ? w.weight / total : 1.0 / static_cast<double>(live.size());
  }
  const bool spin = stepper.go() == nullptr;
  const bool checks_still = stepper.static_surroundings();
  const bool one_draw = length > cap;  // no redraw before the cap: a path alone can be checked
  StillCheck cloud;
  cloud.spin = spin;
  double finished_mass = 0.0;  // of out.finished, kept as they finish
  const auto count_stuck = [&out](const Walker& w) {
    out.stuck += w.weight;
    out.stuck_x_m += w.weight * w.q.x_m;
    out.stuck_y_m += w.weight * w.q.y_m;
    out.stuck_by_stratum[w.stratum] += w.weight;
    out.stuck_x_by_stratum[w.stratum] += w.weight * w.q.x_m;
    out.stuck_y_by_stratum[w.stratum] += w.weight * w.q.y_m;
  };
  // One path from `from` under a draw at `angle` until `until`: how it
  // ended, where, and (for the mean path) its samples. The walker's weight
  // is set when it is committed. Nothing else is touched, so a probe
  // (direction_arcs) steps exactly what the quadrature's own paths step.
  const auto run_path = [&](Walker w, double angle, std::size_t until, std::vector<TrajectoryPoint>* trace,
                            bool keep_samples) {
    PathEnd end;
    StillCheck own;  // this path alone, within a draw that lasts over the window
    own.next = w.cycles + kStillWindowCycles;
    own.spin = spin;
    const exec::Vec2<double> direction{std::cos(angle), std::sin(angle)};
    for (;;) {
      if (trace != nullptr) {
        if (trace->size() >= 2 && at_rest(w.q) && at_rest(trace->back().base)) {
          trace = nullptr;
        } else {
          trace->push_back({w.q, w.error});
        }
      }
      if (const auto exit = stepper.fired(w)) {
        end.outcome = draw_fired(*exit);
        break;
      }
      if (w.cycles >= cap || (checks_still && one_draw && own.still(w.cycles, w.q.x_m, w.q.y_m, w.q.theta_rad, finished_mass))) {
        end.outcome = kDrawPinned;
        break;
      }
      if (w.cycles >= until) {
        end.outcome = kDrawRunning;
        break;
      }
      if (keep_samples && w.cycles % every == 0) end.samples.push_back({w.cycles / every, w.q.x_m, w.q.y_m});
      stepper.step(w, direction);
      ++out.cycles_simulated;
    }
    end.walker = w;
    return end;
  };
  // The first draw's circles: where neighbouring directions of one start
  // end differently, each path's weight becomes its arc's share of the
  // circle's mass (engine/direction_arcs.hpp). Only a circle stepped from
  // one walker: dealt among start points, neighbours differ by where they
  // started as well, and a probe would have to pick one.
  const auto place_on_arcs = [&](const auto& jobs, const std::vector<PathEnd>& ends, const std::vector<Walker>& from,
                                 std::size_t until, std::vector<double>& weights) {
    std::vector<std::vector<std::size_t>> circles;
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (circles.size() <= jobs[j].start) circles.resize(jobs[j].start + 1);
      circles[jobs[j].start].push_back(j);
    }
    for (const std::vector<std::size_t>& circle : circles) {
      if (circle.size() < 2) continue;
      const std::size_t parent = jobs[circle.front()].parent;
      if (!std::all_of(circle.begin(), circle.end(), [&](std::size_t j) { return jobs[j].parent == parent; })) continue;
      std::vector<double> angles;
      std::vector<DrawOutcome> outcomes;
      double mass = 0.0;
      for (const std::size_t j : circle) {
        angles.push_back(jobs[j].angle);
        outcomes.push_back(ends[j].outcome);
        mass += weights[j];
      }
      std::size_t probes = 0;
      ProbedCircle probed{jobs[circle.front()].start, angles, {}, {}};
      const DrawProbe probe = [&](double angle) {
        PathEnd end = run_path(from[parent], angle, until, nullptr, false);
        ProbeEnd p{angle, end.outcome, end.walker.cycles, -1.0, 0.0};
        if (end.outcome >= draw_fired(0)) {
          stepper.settle_phase(end.walker, static_cast<std::size_t>(end.outcome - draw_fired(0)), &p.crossing_c, nullptr,
                               &p.crossing_sd);
        }
        probed.probes.push_back(p);
        return end.outcome;
      };
      const std::vector<double> share =
          direction_arcs(angles, outcomes, probe, DirectionArcLimits{}, probes, &probed.boundaries);
      if (probes == 0) continue;  // all agree: the equal weights stand, bit for bit
      for (std::size_t i = 0; i < circle.size(); ++i) weights[circle[i]] = mass * share[i];
      out.probed.push_back(std::move(probed));
    }
  };
  for (std::size_t segment = 0; !live.empty(); ++segment) {
    if (segment > 0) ++out.redraws;
    const std::size_t until = std::min(cap, (segment + 1) * length);
    std::vector<Walker> children;
    // This draw's paths: (parent, direction index, angle, weight, record slot, start).
    struct Job {
      std::size_t parent, direction, slot, start;
      double angle, weight;
    };
    std::vector<Job> jobs;
    const double turn = static_cast<double>(segment) * kGoldenAngleRad;
    if (segment == 0 && dealt) {
      // Dealt only evenly (above): every start of a group takes directions / n
      // of them; a group's paths are one circle (start index: the group).
      const double per_start = static_cast<double>(directions / per_group);
      for (std::size_t group = 0; group < groups.size(); ++group) {
        for (std::size_t g = 0; g < directions; ++g) {
          const std::size_t s = groups[group][g % per_group];
          jobs.push_back({s, g, group * directions + g, group,
                          2.0 * kPi * (static_cast<double>(g) + 0.5) / static_cast<double>(directions) + turn,
                          live[s].weight / per_start});
        }
      }
    } else {
      for (std::size_t s = 0; s < live.size(); ++s) {
        // More start points than directions: each start's directions turned
        // by a fraction of their spacing (stratified); later draws are one
        // cloud of walkers.
        const double stagger = segment == 0 ? (static_cast<double>(s) + 0.5) / static_cast<double>(n_starts) : 0.5;
        // After the first draw an outer stratum of the entry error redraws
        // over half the directions: what it must tell is mostly whether it
        // gets past the wall, and it weighs 45 % in all (reduce_by_stratum).
        const std::size_t ring = segment > 0 && live[s].stratum != 0
                                     ? std::max<std::size_t>(std::min<std::size_t>(directions, 2), directions / 2)
                                     : directions;
        for (std::size_t j = 0; j < ring; ++j) {
          jobs.push_back({s, j, s * directions + j, segment == 0 ? s : 0,
                          2.0 * kPi * (static_cast<double>(j) + stagger) / static_cast<double>(ring) + turn,
                          live[s].weight / static_cast<double>(ring)});
        }
      }
    }
    // Each path is stepped first and committed after: under the first draw
    // the boundaries between outcomes are placed on the circle
    // (engine/direction_arcs.hpp) and the paths take their arcs' weights.
    std::vector<PathEnd> ends;
    ends.reserve(jobs.size());
    for (const Job& job : jobs) {
      // Recorded until the robot has come to rest for good (a leg waiting
      // at its goal for a message): beyond the record the pose is held.
      std::vector<TrajectoryPoint>* trace =
          (record != nullptr && segment == 0) ? &record->paths[job.slot] : nullptr;
      ends.push_back(run_path(live[job.parent], job.angle, until, trace, true));
    }
    std::vector<double> weights(jobs.size());
    for (std::size_t j = 0; j < jobs.size(); ++j) weights[j] = jobs[j].weight;
    if (segment == 0 && directions >= 2) place_on_arcs(jobs, ends, live, until, weights);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      const Job& job = jobs[j];
      PathEnd& end = ends[j];
      const double weight = weights[j];
      end.walker.weight = weight;
      if (record != nullptr && segment == 0) record->weights[job.slot] = weight;
      for (const PathSample2& p : end.samples) add_sample(p.index, weight, p.x_m, p.y_m);
      if (end.outcome >= draw_fired(0)) {
        FinishedPath done{end.walker, static_cast<std::size_t>(end.outcome - draw_fired(0)), segment, job.direction,
                          job.start, 0.0};
        done.phase_cycles = stepper.settle_phase(done.walker, done.exit, &done.crossing_c, &done.step, &done.crossing_sd);
        if (done.crossing_c >= 0.0) done.phase_var = 1.0 / 12.0;
        out.finished.push_back(done);
        finished_mass += done.walker.weight;
      } else if (end.outcome == kDrawPinned) {
        if (record != nullptr && segment == 0) record->stuck[job.slot] = 1;
        count_stuck(end.walker);
      } else {
        children.push_back(end.walker);
      }
    }
    // Far from the goal and from obstacles the flow is nearly linear in the
    // pose and `directions` walkers carry its spread; near them (the
    // slow-down, where a strong NOISE can hold the robot off its goal) the
    // distribution is shaped by the flow and needs more.
    const bool near = std::any_of(children.begin(), children.end(), [&](const Walker& w) { return stepper.delicate(w); });
    live = reduce_by_stratum(children, near ? keep_near : keep);
    // Redrawn: the walkers are merged at every draw, so the test is on the
    // cloud (its weighted mean pose) rather than on one path.
    if (!live.empty()) {
      double wx = 0.0, wy = 0.0, wt = 0.0, wsum = 0.0;
      for (const Walker& w : live) {
        wx += w.weight * w.q.x_m;
        wy += w.weight * w.q.y_m;
        wt += w.weight * w.q.theta_rad;
        wsum += w.weight;
      }
      // What is left may be a vanishing remainder (1e-12 of the mass, down to
      // 1e-236 on gen_5062, orbiting the goal): not worth a cycle more.
      if (wsum < kNegligibleLiveMass ||
          (checks_still && cloud.still(live.front().cycles, wx / wsum, wy / wsum, wt / wsum, finished_mass))) {
        for (const Walker& w : live) count_stuck(w);
        live.clear();
      }
    }
  }

  // Finished paths stay where they ended for the rest of the mean path.
  const std::size_t samples = sx.size();
  for (const FinishedPath& p : out.finished) {
    for (std::size_t i = (p.walker.cycles + every - 1) / every; i < samples; ++i) {
      add_sample(i, p.walker.weight, p.walker.q.x_m, p.walker.q.y_m);
    }
  }
  for (std::size_t i = 0; i < samples; ++i) {
    if (!(sw[i] > 0.0)) continue;
    PathSample s;
    s.offset_s = static_cast<double>(i);
    s.x_m = sx[i] / sw[i];
    s.y_m = sy[i] / sw[i];
    s.var_xx = std::max(0.0, sxx[i] / sw[i] - s.x_m * s.x_m);
    s.var_yy = std::max(0.0, syy[i] / sw[i] - s.y_m * s.y_m);
    s.var_xy = std::clamp(sxy[i] / sw[i] - s.x_m * s.y_m, -std::sqrt(s.var_xx * s.var_yy), std::sqrt(s.var_xx * s.var_yy));
    out.mean_path.push_back(s);
  }
  return out;
}

}  // namespace p3at::verifier::engine
