#include <doctest/doctest.h>

#include <string>

#include "p3at/hal/url.hpp"

using p3at::Error;
using p3at::hal::parse_url;
using p3at::hal::Url;

namespace {

// Parses a URL that must be rejected; returns the error message after checking the code.
std::string rejection(const std::string& text) {
  auto url = parse_url(text);
  REQUIRE_MESSAGE(!url.ok(), "accepted: " << text);
  CHECK(url.error().code == Error::Code::invalid_argument);
  // Every message names the URL it is about.
  CHECK_MESSAGE(url.error().message.find(text) != std::string::npos, url.error().message);
  return url.error().message;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("tcp URL with host and port") {
  auto url = parse_url("tcp://127.0.0.1:8101");
  REQUIRE(url.ok());
  CHECK(url->scheme == "tcp");
  CHECK(url->host == "127.0.0.1");
  CHECK(url->port == 8101);
  CHECK(url->path.empty());
  CHECK(url->query.empty());
}

TEST_CASE("serial URL with empty authority, path and query") {
  auto url = parse_url("serial:///dev/ttyS0?baud=9600");
  REQUIRE(url.ok());
  CHECK(url->scheme == "serial");
  CHECK(url->host.empty());
  CHECK(url->port == -1);
  CHECK(url->path == "/dev/ttyS0");
  REQUIRE(url->query.size() == 1);
  CHECK(url->query.at("baud") == "9600");
  CHECK(url->query_or("baud", "x") == "9600");
  CHECK(url->query_or("parity", "none") == "none");
}

TEST_CASE("scheme is lower-cased, host kept as written") {
  auto url = parse_url("TCP://Robot-1.local:80");
  REQUIRE(url.ok());
  CHECK(url->scheme == "tcp");
  CHECK(url->host == "Robot-1.local");
  CHECK(url->port == 80);
}

TEST_CASE("host without port, and schemes of other backends") {
  auto can = parse_url("socketcan://can0");
  REQUIRE(can.ok());
  CHECK(can->scheme == "socketcan");
  CHECK(can->host == "can0");
  CHECK(can->port == -1);

  auto sim = parse_url("sim://robot1");
  REQUIRE(sim.ok());
  CHECK(sim->host == "robot1");

  auto lcm = parse_url("udpm://239.255.76.67:7667?ttl=0");
  REQUIRE(lcm.ok());
  CHECK(lcm->scheme == "udpm");
  CHECK(lcm->host == "239.255.76.67");
  CHECK(lcm->port == 7667);
  CHECK(lcm->query_or("ttl", "1") == "0");

  auto memq = parse_url("memq://");
  REQUIRE(memq.ok());
  CHECK(memq->scheme == "memq");
  CHECK(memq->host.empty());
}

TEST_CASE("bracketed IPv6 host, with and without port") {
  auto with_port = parse_url("tcp://[::1]:8101");
  REQUIRE(with_port.ok());
  CHECK(with_port->host == "::1");
  CHECK(with_port->port == 8101);

  auto without = parse_url("tcp://[fe80::1:2]/x");
  REQUIRE(without.ok());
  CHECK(without->host == "fe80::1:2");
  CHECK(without->port == -1);
  CHECK(without->path == "/x");

  auto mapped = parse_url("tcp://[::ffff:127.0.0.1]:1");
  REQUIRE(mapped.ok());
  CHECK(mapped->host == "::ffff:127.0.0.1");
}

TEST_CASE("port range edges") {
  auto zero = parse_url("tcp://h:0");
  REQUIRE(zero.ok());
  CHECK(zero->port == 0);
  auto top = parse_url("tcp://h:65535");
  REQUIRE(top.ok());
  CHECK(top->port == 65535);
  auto padded = parse_url("tcp://h:08101");
  REQUIRE(padded.ok());
  CHECK(padded->port == 8101);
}

TEST_CASE("query with several keys, empty value and stray separators") {
  auto url = parse_url("serial:///dev/ttyUSB0?baud=115200&name=&&mode=raw&");
  REQUIRE(url.ok());
  CHECK(url->path == "/dev/ttyUSB0");
  CHECK(url->query.size() == 3);
  CHECK(url->query.at("baud") == "115200");
  CHECK(url->query.at("name").empty());
  CHECK(url->query.at("mode") == "raw");
  CHECK(url->query_or("name", "fallback").empty());  // present but empty is not absent
}

TEST_CASE("value may contain '=' and the path keeps every segment") {
  auto url = parse_url("x://h/a/b/c?expr=a=b");
  REQUIRE(url.ok());
  CHECK(url->path == "/a/b/c");
  CHECK(url->query.at("expr") == "a=b");
}

TEST_CASE("missing scheme separator") {
  CHECK(contains(rejection("127.0.0.1:8101"), "expected scheme://"));
  CHECK(contains(rejection(""), "expected scheme://"));
  CHECK(contains(rejection("tcp:/127.0.0.1:8101"), "expected scheme://"));
}

TEST_CASE("bad scheme") {
  CHECK(contains(rejection("://host"), "scheme ''"));
  CHECK(contains(rejection("1tcp://host"), "must start with a letter"));
  CHECK(contains(rejection("t_p://host"), "must start with a letter"));
}

TEST_CASE("spaces, control characters and fragments") {
  CHECK(contains(rejection("tcp://host :1"), "spaces or control"));
  CHECK(contains(rejection(std::string("tcp://h\x01:1")), "spaces or control"));
  CHECK(contains(rejection("tcp://h:1\n"), "spaces or control"));
  CHECK(contains(rejection("tcp://h:1/#frag"), "fragments"));
}

TEST_CASE("bad ports") {
  CHECK(contains(rejection("tcp://h:"), "expected a port number"));
  CHECK(contains(rejection("tcp://h:abc"), "not a number"));
  CHECK(contains(rejection("tcp://h:-1"), "not a number"));
  CHECK(contains(rejection("tcp://h:+80"), "not a number"));
  CHECK(contains(rejection("tcp://h:65536"), "out of range"));
  CHECK(contains(rejection("tcp://h:99999999999999999999"), "out of range"));
  CHECK(contains(rejection("tcp://[::1]:"), "expected a port number"));
  CHECK(contains(rejection("tcp://[::1]:70000"), "out of range"));
}

TEST_CASE("bad hosts") {
  CHECK(contains(rejection("tcp://:8101"), "expected a host"));
  CHECK(contains(rejection("tcp://ho$t:1"), "host 'ho$t'"));
  CHECK(contains(rejection("tcp://::1:8101"), "must be in brackets"));
  CHECK(contains(rejection("tcp://user@host:1"), "user information"));
}

TEST_CASE("bad IPv6 literals") {
  CHECK(contains(rejection("tcp://[::1:8101"), "expected ']'"));
  CHECK(contains(rejection("tcp://[]:1"), "is not an IPv6 address"));
  CHECK(contains(rejection("tcp://[host]:1"), "is not an IPv6 address"));
  CHECK(contains(rejection("tcp://[::1]8101"), "expected ':PORT' or nothing after ']'"));
}

TEST_CASE("bad query items") {
  CHECK(contains(rejection("serial:///dev/ttyS0?baud"), "has no '='"));
  CHECK(contains(rejection("serial:///dev/ttyS0?=9600"), "empty key"));
  CHECK(contains(rejection("serial:///dev/ttyS0?baud=1&baud=2"), "appears twice"));
}
