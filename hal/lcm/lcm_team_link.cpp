// LcmTeamLink: DatagramTeamLink over LCM. Non-blocking: poll() drains what
// LCM has queued with handleTimeout(0) and never waits.
#include "p3at/hal/lcm_team_link.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <string>

#include "p3at/team_link/datagram_team_link.hpp"
#include "p3at/hal/url.hpp"

namespace p3at::hal {

namespace {

// A poll() handles at most this many messages, so a flood cannot hold up the
// executive's cycle; the rest wait in LCM's queue for the next poll().
constexpr int kMaxMessagesPerPoll = 1024;

std::int64_t micros(std::chrono::system_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count();
}
std::int64_t micros(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count();
}

class LcmTeamLink final : public DatagramTeamLink {
 public:
  LcmTeamLink(TeamProtocol protocol, std::unique_ptr<lcm::LCM> lcm, std::string url)
      : DatagramTeamLink(std::move(protocol)), lcm_(std::move(lcm)), url_(std::move(url)) {}

  ~LcmTeamLink() override {
    for (auto* s : subscriptions_) lcm_->unsubscribe(s);
  }

  Status subscribe() {
    // Telemetry too: in-mission re-verification reads where the teammates are.
    for (const auto channel : {TeamChannel::notify, TeamChannel::status, TeamChannel::gate, TeamChannel::telemetry}) {
      auto* s = lcm_->subscribe(std::string(channel_name(channel)), &LcmTeamLink::on_message, this);
      if (s == nullptr) {
        return make_error(Error::Code::io, "team link " + url_ + ": cannot subscribe to " +
                                               std::string(channel_name(channel)));
      }
      subscriptions_.push_back(s);
    }
    return {};
  }

 private:
  Status transmit(const TeamDatagram& datagram, std::int64_t) override {
    const std::string channel(channel_name(datagram.channel));
    if (lcm_->publish(channel, datagram.bytes.data(), static_cast<unsigned int>(datagram.bytes.size())) != 0) {
      return make_error(Error::Code::io, "team link " + url_ + ": cannot publish on " + channel);
    }
    return {};
  }

  Status collect(std::int64_t, std::vector<TeamDatagram>& arrived) override {
    sink_ = &arrived;
    int handled = 0;
    int rc = 0;
    while (handled < kMaxMessagesPerPoll && (rc = lcm_->handleTimeout(0)) > 0) ++handled;
    sink_ = nullptr;
    if (rc < 0) return make_error(Error::Code::io, "team link " + url_ + ": LCM failed to receive");
    return {};
  }

  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    const auto which = channel_from_name(channel);
    if (sink_ == nullptr || !which || rbuf == nullptr) return;
    const auto* data = static_cast<const std::uint8_t*>(rbuf->data);
    sink_->push_back({*which, std::vector<std::uint8_t>(data, data + rbuf->data_size)});
  }

  std::unique_ptr<lcm::LCM> lcm_;
  std::string url_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::vector<TeamDatagram>* sink_ = nullptr;  ///< set only while collect() runs
};

}  // namespace

Result<std::unique_ptr<gate::VerdictLink>> open_lcm_team_link(std::string_view lcm_url, TeamLinkConfig config,
                                                     const TeamKey& key) {
  const std::string url(lcm_url);
  auto parsed = parse_url(url);
  if (!parsed) return make_error(Error::Code::invalid_argument, "team link: " + parsed.error().message);
  if (parsed->scheme != "udpm" && parsed->scheme != "memq") {
    return make_error(Error::Code::invalid_argument,
                      "team link: unsupported LCM URL '" + url + "' (expected udpm://GROUP:PORT?ttl=N or memq://)");
  }
  if (parsed->scheme == "udpm") {
    // LCM would only say it cannot open; a malformed URL is the caller's input error.
    in_addr group{};
    if (::inet_pton(AF_INET, parsed->host.c_str(), &group) != 1 || (ntohl(group.s_addr) >> 28) != 14) {
      return make_error(Error::Code::invalid_argument, "team link: LCM URL '" + url + "': '" + parsed->host +
                                                           "' is not an IPv4 multicast group (224.0.0.0/4)");
    }
    if (parsed->port <= 0) {
      return make_error(Error::Code::invalid_argument,
                        "team link: LCM URL '" + url + "': needs a port (udpm://GROUP:PORT?ttl=N)");
    }
  }
  const auto wall = std::chrono::system_clock::now();
  const auto steady = std::chrono::steady_clock::now();
  config.first_seq = static_cast<std::uint64_t>(micros(wall));
  config.utime_offset_us = micros(wall) - micros(steady);
  auto protocol = TeamProtocol::create(std::move(config), key);
  if (!protocol) return protocol.error();

  auto lcm = std::make_unique<lcm::LCM>(url);
  if (!lcm->good()) {
    return make_error(Error::Code::io, "team link: LCM cannot open '" + url +
                                           "' (is there a multicast route? see docs/team-link.md)");
  }
  auto link = std::make_unique<LcmTeamLink>(std::move(protocol.value()), std::move(lcm), url);
  if (auto s = link->subscribe(); !s) return s.error();
  return std::unique_ptr<gate::VerdictLink>(std::move(link));
}

}  // namespace p3at::hal
