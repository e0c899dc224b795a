#include "p3at/sim/radio.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::sim {

namespace {

// Keeps a pathological draw (huge sigma) from overflowing the conversion to
// microseconds; an hour is "never" for a mission.
constexpr double kMaxLatencyMs = 3.6e6;

Status bad_param(const std::string& key, const std::string& expected) {
  return make_error(Error::Code::invalid_argument, "radio: " + key + " must be " + expected);
}

}  // namespace

Status validate_radio_params(const RadioParams& p) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(p.latency_min_ms) || p.latency_min_ms < 0) return bad_param("latency_min_ms", ">= 0");
  if (!finite(p.latency_median_ms) || p.latency_median_ms <= 0) return bad_param("latency_median_ms", "> 0");
  if (!finite(p.latency_sigma) || p.latency_sigma < 0) return bad_param("latency_sigma", ">= 0");
  if (!finite(p.slow_probability) || p.slow_probability < 0 || p.slow_probability > 1) {
    return bad_param("slow_probability", "in [0, 1]");
  }
  if (!finite(p.slow_median_ms) || p.slow_median_ms <= 0) return bad_param("slow_median_ms", "> 0");
  if (!finite(p.slow_sigma) || p.slow_sigma < 0) return bad_param("slow_sigma", ">= 0");
  if (!finite(p.loss_probability) || p.loss_probability < 0 || p.loss_probability > 1) {
    return bad_param("loss_probability", "in [0, 1]");
  }
  return {};
}

Result<std::unique_ptr<SimRadio>> SimRadio::create(const RadioParams& params, std::uint64_t seed) {
  if (auto s = validate_radio_params(params); !s) return s.error();
  return std::unique_ptr<SimRadio>(new SimRadio(params, seed));
}

SimRadio::Endpoint SimRadio::attach(std::string name) {
  endpoints_.push_back({std::move(name), {}});
  return endpoints_.size() - 1;
}

Rng& SimRadio::link_rng(Endpoint from, Endpoint to, hal::TeamChannel channel) {
  const auto key = std::make_tuple(from, to, static_cast<int>(channel));
  auto it = links_.find(key);
  if (it == links_.end()) {
    // One independent stream per link and channel, so a robot's telemetry
    // rate or a third robot's traffic does not shift another link's draws.
    const std::uint64_t from_bits = from;
    const std::uint64_t to_bits = to;
    const std::uint64_t stream = (from_bits << 40) ^ (to_bits << 8) ^ static_cast<std::uint64_t>(channel);
    it = links_.emplace(key, Rng(seed_, stream)).first;
  }
  return it->second;
}

std::int64_t SimRadio::draw_latency_us(Rng& rng) const {
  const bool slow = rng.uniform() < params_.slow_probability;
  const double median_ms = slow ? params_.slow_median_ms : params_.latency_median_ms;
  const double sigma = slow ? params_.slow_sigma : params_.latency_sigma;
  const double latency_ms = params_.latency_min_ms + median_ms * std::exp(rng.gaussian(sigma));
  return std::llround(std::min(latency_ms, kMaxLatencyMs) * 1000.0);
}

void SimRadio::send(Endpoint from, const hal::TeamDatagram& datagram, std::int64_t now_us) {
  if (from >= endpoints_.size()) return;
  ++stats_.sent;
  const std::uint64_t order = next_order_++;
  for (Endpoint to = 0; to < endpoints_.size(); ++to) {
    if (to == from) continue;
    Rng& rng = link_rng(from, to, datagram.channel);
    // Both draws are always made, so a link's sequence of draws depends only
    // on how many datagrams it carried.
    const bool lost = rng.uniform() < params_.loss_probability;
    const std::int64_t latency_us = draw_latency_us(rng);
    if (lost) {
      ++stats_.lost;
      continue;
    }
    endpoints_[to].queue.push({now_us + latency_us, order, datagram});
  }
}

void SimRadio::receive(Endpoint to, std::int64_t now_us, std::vector<hal::TeamDatagram>& out) {
  if (to >= endpoints_.size()) return;
  auto& queue = endpoints_[to].queue;
  while (!queue.empty() && queue.top().arrival_us <= now_us) {
    out.push_back(queue.top().datagram);
    queue.pop();
    ++stats_.delivered;
  }
}

std::optional<std::int64_t> SimRadio::next_arrival_us(Endpoint to) const {
  if (to >= endpoints_.size() || endpoints_[to].queue.empty()) return std::nullopt;
  return endpoints_[to].queue.top().arrival_us;
}

Result<std::unique_ptr<SimTeamLink>> SimTeamLink::create(SimRadio& radio, hal::TeamLinkConfig config,
                                                         const hal::TeamKey& key) {
  const std::string self = config.self;
  auto protocol = hal::TeamProtocol::create(std::move(config), key);
  if (!protocol) return protocol.error();
  const SimRadio::Endpoint endpoint = radio.attach(self);
  return std::unique_ptr<SimTeamLink>(new SimTeamLink(std::move(protocol.value()), radio, endpoint));
}

Status SimTeamLink::transmit(const hal::TeamDatagram& datagram, std::int64_t now_us) {
  radio_.send(endpoint_, datagram, now_us);
  return {};
}

Status SimTeamLink::collect(std::int64_t now_us, std::vector<hal::TeamDatagram>& arrived) {
  radio_.receive(endpoint_, now_us, arrived);
  return {};
}

}  // namespace p3at::sim
