#include "engine/separations.hpp"

#include <algorithm>
#include <limits>

namespace p3at::verifier::engine {

void Timeline::note(double time_s, const Gaussian2& position, double rigid_s) {
  while (!points_.empty() && points_.back().time_s >= time_s) points_.pop_back();
  points_.push_back({time_s, position, rigid_s});
}

Gaussian2 Timeline::at(double time_s) const {
  if (points_.empty()) return {};
  if (time_s <= points_.front().time_s) return points_.front().position;
  if (time_s >= points_.back().time_s) return points_.back().position;
  const auto after = std::upper_bound(points_.begin(), points_.end(), time_s,
                                      [](double t, const TimedPosition& p) { return t < p.time_s; });
  const TimedPosition& b = *after;
  const TimedPosition& a = *(after - 1);
  const double span = b.time_s - a.time_s;
  const double f = span > 0.0 ? (time_s - a.time_s) / span : 1.0;
  Gaussian2 g;
  g.mean = (1.0 - f) * a.position.mean + f * b.position.mean;
  g.cov = (1.0 - f) * a.position.cov + f * b.position.cov;
  return g;
}

double Timeline::rigid_at(double time_s) const {
  if (points_.empty()) return 0.0;
  const auto after = std::upper_bound(points_.begin(), points_.end(), time_s,
                                      [](double t, const TimedPosition& p) { return t < p.time_s; });
  return after == points_.begin() ? points_.front().rigid_s : (after - 1)->rigid_s;
}

namespace {

struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
};

Box bounds(const Timeline& t) {
  Box b;
  for (const TimedPosition& p : t.points()) {
    b.x0 = std::min(b.x0, p.position.mean.x());
    b.y0 = std::min(b.y0, p.position.mean.y());
    b.x1 = std::max(b.x1, p.position.mean.x());
    b.y1 = std::max(b.y1, p.position.mean.y());
  }
  return b;
}

// Whether two robots' means ever come within `reach` of each other's box (a
// cheap test that leaves most pairs of a large team out).
bool boxes_within(const Box& a, const Box& b, double reach) {
  const double gx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1});
  const double gy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
  return gx * gx + gy * gy <= reach * reach;
}

}  // namespace

std::vector<SeparationSample> pair_separations(const std::vector<const Timeline*>& robots, double horizon_m) {
  std::vector<SeparationSample> out;
  std::vector<Box> boxes;
  boxes.reserve(robots.size());
  for (const Timeline* t : robots) boxes.push_back(bounds(*t));
  std::vector<double> times;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    if (robots[i]->empty()) continue;
    for (std::size_t j = i + 1; j < robots.size(); ++j) {
      if (robots[j]->empty() || !boxes_within(boxes[i], boxes[j], horizon_m)) continue;
      times.clear();
      for (const TimedPosition& p : robots[i]->points()) times.push_back(p.time_s);
      for (const TimedPosition& p : robots[j]->points()) times.push_back(p.time_s);
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end()), times.end());
      bool previous_kept = false, parted = false;
      for (const double t : times) {
        const Gaussian2 a = robots[i]->at(t), b = robots[j]->at(t);
        SeparationSample s;
        s.robot_i = i;
        s.robot_j = j;
        s.time_s = t;
        s.difference.mean = a.mean - b.mean;
        s.difference.cov = a.cov + b.cov;
        s.rigid_s = std::min(robots[i]->rigid_at(t), robots[j]->rigid_at(t));
        const bool kept = s.difference.mean.norm() <= horizon_m;
        if (kept) {
          s.joined = previous_kept;
          out.push_back(s);
        } else if (!parted) {
          parted = true;
          s.beyond_horizon = true;
          out.push_back(s);
        }
        previous_kept = kept;
      }
    }
  }
  return out;
}

}  // namespace p3at::verifier::engine
