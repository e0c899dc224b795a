#pragma once
/// The simulated radio for team messages (fast time): one shared medium per
/// simulated run, carrying the same authenticated datagrams as LCM, with a
/// latency distribution and losses drawn from the run's seed, driven only by
/// the synthetic times given to it. Same seed, same calls → same deliveries.
///
/// SimTeamLink is a robot's hal::TeamLink on it: the very protocol code the
/// LCM backend runs (hal::DatagramTeamLink / hal::TeamProtocol).

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/team_link/datagram_team_link.hpp"
#include "p3at/team_link/team_key.hpp"
#include "p3at/team_link/team_protocol.hpp"
#include "p3at/team_link/team_wire.hpp"
#include "p3at/sim/rng.hpp"

namespace p3at::sim {

/// Delivery model, per (sender, receiver) pair and per datagram:
///   lost with probability loss_probability; otherwise delayed by
///   latency_min_ms + L, where L is log-normal with median latency_median_ms
///   and shape latency_sigma (the standard deviation of ln L), except that with
///   probability slow_probability L comes from a second log-normal
///   (slow_median_ms, slow_sigma): a mixture for the occasional slow delivery
///   (retries at the MAC layer, a busy channel).
/// World-file keys (block `radio:`) have the same names.
struct RadioParams {
  double latency_min_ms = 1.0;     ///< >= 0
  double latency_median_ms = 4.0;  ///< > 0
  double latency_sigma = 0.5;      ///< >= 0 (0: always the median)
  double slow_probability = 0.0;   ///< in [0, 1]
  double slow_median_ms = 50.0;    ///< > 0
  double slow_sigma = 0.5;         ///< >= 0
  double loss_probability = 0.0;   ///< in [0, 1]
};

/// Ok, or invalid_argument naming the key that is out of range (or not finite).
Status validate_radio_params(const RadioParams& params);

/// The shared medium. Not thread-safe: one thread drives a fast-time run.
class SimRadio {
 public:
  using Endpoint = std::size_t;

  /// Counters over all endpoints; deliveries are counted per receiver.
  struct Stats {
    std::uint64_t sent = 0;       ///< datagrams handed to send()
    std::uint64_t delivered = 0;  ///< handed to a receiver by receive()
    std::uint64_t lost = 0;       ///< dropped by the loss model
  };

  /// invalid_argument when validate_radio_params() fails.
  static Result<std::unique_ptr<SimRadio>> create(const RadioParams& params, std::uint64_t seed);

  SimRadio(const SimRadio&) = delete;
  SimRadio& operator=(const SimRadio&) = delete;

  /// Adds a listener/sender (a robot, or a test's intruder). Endpoints are
  /// numbered in attach order; each hears only what is sent after it attached.
  Endpoint attach(std::string name);

  /// Broadcasts `datagram` from `from` at time `now_us` to every other endpoint,
  /// each with its own loss and latency draw. An unknown `from` is ignored.
  void send(Endpoint from, const hal::TeamDatagram& datagram, std::int64_t now_us);

  /// Appends to `out` what has reached `to` by `now_us`, in arrival order
  /// (ties in send order).
  void receive(Endpoint to, std::int64_t now_us, std::vector<hal::TeamDatagram>& out);

  /// Time of the next arrival waiting for `to`, if any (for event-driven loops).
  std::optional<std::int64_t> next_arrival_us(Endpoint to) const;

  const Stats& stats() const { return stats_; }
  const RadioParams& params() const { return params_; }
  const std::string& name(Endpoint endpoint) const { return endpoints_.at(endpoint).name; }

 private:
  struct InFlight {
    std::int64_t arrival_us = 0;
    std::uint64_t order = 0;  ///< global send order, breaks ties
    hal::TeamDatagram datagram;
    bool operator>(const InFlight& other) const {
      return std::tie(arrival_us, order) > std::tie(other.arrival_us, other.order);
    }
  };
  struct EndpointState {
    std::string name;
    std::priority_queue<InFlight, std::vector<InFlight>, std::greater<>> queue;
  };

  SimRadio(const RadioParams& params, std::uint64_t seed) : params_(params), seed_(seed) {}
  Rng& link_rng(Endpoint from, Endpoint to, hal::TeamChannel channel);
  /// Latency of one delivery in microseconds, from the link's generator.
  std::int64_t draw_latency_us(Rng& rng) const;

  RadioParams params_;
  std::uint64_t seed_;
  std::vector<EndpointState> endpoints_;
  std::map<std::tuple<Endpoint, Endpoint, int>, Rng> links_;  ///< one generator per (from, to, channel)
  std::uint64_t next_order_ = 0;
  Stats stats_;
};

/// A simulated robot's hal::TeamLink on a SimRadio (which must outlive it).
class SimTeamLink final : public hal::DatagramTeamLink {
 public:
  /// Attaches to the radio as config.self. config.first_seq is used as given
  /// (deterministic; 1 by default). invalid_argument for a bad config.
  static Result<std::unique_ptr<SimTeamLink>> create(SimRadio& radio, hal::TeamLinkConfig config,
                                                     const hal::TeamKey& key);

  SimRadio::Endpoint endpoint() const { return endpoint_; }

 private:
  SimTeamLink(hal::TeamProtocol protocol, SimRadio& radio, SimRadio::Endpoint endpoint)
      : hal::DatagramTeamLink(std::move(protocol)), radio_(radio), endpoint_(endpoint) {}

  Status transmit(const hal::TeamDatagram& datagram, std::int64_t now_us) override;
  Status collect(std::int64_t now_us, std::vector<hal::TeamDatagram>& arrived) override;

  SimRadio& radio_;
  SimRadio::Endpoint endpoint_;
};

}  // namespace p3at::sim
