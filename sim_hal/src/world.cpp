#include "p3at/sim/world.hpp"

namespace p3at::sim {

World::World(const WorldConfig& config, std::uint64_t seed) : walls_(config.walls) {
  robots_.reserve(config.robots.size());
  for (std::size_t i = 0; i < config.robots.size(); ++i) robots_.emplace_back(config.robots[i], seed, i);
  others_.resize(robots_.empty() ? 0 : robots_.size() - 1);
}

std::optional<std::size_t> World::find_robot(std::string_view name) const {
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i].name() == name) return i;
  }
  return std::nullopt;
}

void World::step() {
  constexpr std::int64_t substep_us = kCycleUs / kSubstepsPerCycle;
  constexpr double dt_s = static_cast<double>(substep_us) / 1e6;
  for (SimRobot& r : robots_) r.begin_cycle(walls_);
  for (int k = 1; k <= kSubstepsPerCycle; ++k) {
    const std::int64_t now_us = time_us_ + k * substep_us;
    for (std::size_t i = 0; i < robots_.size(); ++i) {
      collect_others(i);
      robots_[i].step(now_us, dt_s, others_);
    }
  }
  time_us_ += kCycleUs;
  ++cycles_;
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    collect_others(i);
    robots_[i].update_sonar(walls_, others_);
  }
  clock_.advance_to_us(time_us_);
}

void World::collect_others(std::size_t index) {
  // others_ has robot_count() - 1 elements from construction on.
  std::size_t k = 0;
  for (std::size_t j = 0; j < robots_.size(); ++j) {
    if (j != index) others_[k++] = robots_[j].box();
  }
}

void World::advance_to(std::int64_t time_us) {
  while (time_us_ + kCycleUs <= time_us) step();
}

}  // namespace p3at::sim
