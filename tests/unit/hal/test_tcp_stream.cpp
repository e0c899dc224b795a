#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/tcp_listener.hpp"

using p3at::Error;
using p3at::hal::ByteStream;
using p3at::hal::open_byte_stream;
using p3at::hal::TcpListener;

namespace {

using Clock = std::chrono::steady_clock;

long long elapsed_ms(Clock::time_point since) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - since).count();
}

std::string url_for(int port) { return "tcp://127.0.0.1:" + std::to_string(port); }

// A connected pair over loopback: client from open_byte_stream, server from accept.
struct Pair {
  std::unique_ptr<TcpListener> listener;
  std::unique_ptr<ByteStream> client;
  std::unique_ptr<ByteStream> server;
};

Pair connect_pair() {
  Pair p;
  auto listener = TcpListener::listen("127.0.0.1", 0);
  REQUIRE_MESSAGE(listener.ok(), (listener.ok() ? "" : listener.error().message));
  p.listener = std::move(listener).value();
  REQUIRE(p.listener->port() > 0);
  auto client = open_byte_stream(url_for(p.listener->port()), 2000);
  REQUIRE_MESSAGE(client.ok(), (client.ok() ? "" : client.error().message));
  p.client = std::move(client).value();
  auto server = p.listener->accept(2000);
  REQUIRE(server.ok());
  REQUIRE(server.value() != nullptr);
  p.server = std::move(server).value();
  return p;
}

// Reads exactly `count` bytes or fails the test.
std::vector<std::uint8_t> read_exactly(ByteStream& stream, std::size_t count, std::size_t chunk = 4096) {
  std::vector<std::uint8_t> out;
  std::vector<std::uint8_t> buffer(chunk);
  const auto start = Clock::now();
  while (out.size() < count && elapsed_ms(start) < 10'000) {
    const std::size_t want = std::min(chunk, count - out.size());
    auto n = stream.read_some(std::span(buffer.data(), want), 500);
    REQUIRE_MESSAGE(n.ok(), (n.ok() ? "" : n.error().message));
    out.insert(out.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*n));
  }
  REQUIRE(out.size() == count);
  return out;
}

std::vector<std::uint8_t> pattern(std::size_t size, std::uint32_t seed) {
  std::vector<std::uint8_t> v(size);
  std::uint32_t x = seed;
  for (auto& b : v) {
    x = x * 1664525u + 1013904223u;  // LCG: a pattern that differs at every offset
    b = static_cast<std::uint8_t>(x >> 24);
  }
  return v;
}

}  // namespace

TEST_CASE("bytes flow both ways over loopback") {
  Pair p = connect_pair();
  CHECK(p.client->describe() == url_for(p.listener->port()));
  CHECK(p.server->describe().rfind("tcp://127.0.0.1:", 0) == 0);

  const std::vector<std::uint8_t> hello = {0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00};
  REQUIRE(p.client->write_all(hello).ok());
  CHECK(read_exactly(*p.server, hello.size()) == hello);

  const std::vector<std::uint8_t> reply = {0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01, 0x42};
  REQUIRE(p.server->write_all(reply).ok());
  CHECK(read_exactly(*p.client, reply.size()) == reply);

  // An empty write is a no-op, an empty read returns 0 without waiting.
  CHECK(p.client->write_all({}).ok());
  std::vector<std::uint8_t> none;
  auto n = p.client->read_some(none, 1000);
  REQUIRE(n.ok());
  CHECK(*n == 0);
}

TEST_CASE("large transfers arrive intact whatever the chunking") {
  Pair p = connect_pair();
  const std::vector<std::uint8_t> up = pattern(4 * 1024 * 1024, 1);
  const std::vector<std::uint8_t> down = pattern(1024 * 1024 + 7, 2);

  std::vector<std::uint8_t> received_up;
  std::thread server_side([&] {
    received_up = read_exactly(*p.server, up.size(), 1500);  // odd chunk size on purpose
    // Then answer in many small writes.
    for (std::size_t off = 0; off < down.size(); off += 333) {
      const std::size_t len = std::min<std::size_t>(333, down.size() - off);
      REQUIRE(p.server->write_all(std::span(down.data() + off, len)).ok());
    }
  });
  // One write_all much larger than the socket buffer: exercises partial sends.
  const auto st = p.client->write_all(up);
  CHECK_MESSAGE(st.ok(), (st.ok() ? "" : st.error().message));
  const std::vector<std::uint8_t> received_down = read_exactly(*p.client, down.size(), 65536);
  server_side.join();
  CHECK(received_up == up);
  CHECK(received_down == down);
}

TEST_CASE("read_some times out with 0 bytes") {
  Pair p = connect_pair();
  std::vector<std::uint8_t> buffer(64);

  auto start = Clock::now();
  auto polled = p.client->read_some(buffer, 0);
  REQUIRE(polled.ok());
  CHECK(*polled == 0);
  CHECK(elapsed_ms(start) < 50);

  start = Clock::now();
  auto waited = p.client->read_some(buffer, 100);
  REQUIRE(waited.ok());
  CHECK(*waited == 0);
  const long long ms = elapsed_ms(start);
  CHECK(ms >= 95);
  CHECK(ms < 1000);

  // Data arriving during the wait ends it early.
  std::thread late([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::vector<std::uint8_t> one = {7};
    CHECK(p.server->write_all(one).ok());
  });
  start = Clock::now();
  auto got = p.client->read_some(buffer, 5000);
  late.join();
  REQUIRE(got.ok());
  CHECK(*got == 1);
  CHECK(buffer[0] == 7);
  CHECK(elapsed_ms(start) < 2000);
}

TEST_CASE("peer close is reported as Error::Code::closed, never SIGPIPE") {
  Pair p = connect_pair();
  p.server->close();
  std::vector<std::uint8_t> buffer(16);
  auto n = p.client->read_some(buffer, 1000);
  REQUIRE_FALSE(n.ok());
  CHECK(n.error().code == Error::Code::closed);
  CHECK(n.error().message.find(p.client->describe()) != std::string::npos);

  // Writing to a closed peer: the first send may still be accepted locally;
  // the following ones fail with EPIPE/ECONNRESET, which must come back as
  // `closed` (with SIGPIPE raised, this test process would die instead).
  const std::vector<std::uint8_t> data(1024, 0x55);
  p3at::Status st;
  for (int i = 0; i < 100 && st.ok(); ++i) {
    st = p.client->write_all(data);
    if (st.ok()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::closed);
}

TEST_CASE("a closed stream refuses further calls") {
  Pair p = connect_pair();
  p.client->close();
  p.client->close();  // idempotent
  std::vector<std::uint8_t> buffer(4);
  auto n = p.client->read_some(buffer, 10);
  REQUIRE_FALSE(n.ok());
  CHECK(n.error().code == Error::Code::closed);
  auto st = p.client->write_all(buffer);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::closed);
}

TEST_CASE("write_all gives up with a timeout when the peer stops reading") {
  Pair p = connect_pair();
  // Far more than the kernel will buffer for a peer that never reads.
  const std::vector<std::uint8_t> flood(64 * 1024 * 1024, 0xAA);
  const auto start = Clock::now();
  auto st = p.client->write_all(flood);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::timeout);
  CHECK(st.error().message.find("not reading") != std::string::npos);
  CHECK(elapsed_ms(start) < 10'000);
}

TEST_CASE("connecting to a port nobody listens on is `refused`") {
  int port = 0;
  {
    auto listener = TcpListener::listen("127.0.0.1", 0);
    REQUIRE(listener.ok());
    port = (*listener)->port();
  }  // closed: the port is now free
  const std::string url = url_for(port);
  auto s = open_byte_stream(url, 2000);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().code == Error::Code::refused);
  CHECK(s.error().message == url + ": connection refused");
}

TEST_CASE("a connect that gets no answer times out within the budget") {
  // A listener that never accepts: once its queue is full the kernel drops
  // further SYNs, so the next connect gets no answer at all.
  auto listener = TcpListener::listen("127.0.0.1", 0);
  REQUIRE(listener.ok());
  const std::string url = url_for((*listener)->port());
  std::vector<std::unique_ptr<ByteStream>> queued;
  bool timed_out = false;
  for (int i = 0; i < 256 && !timed_out; ++i) {
    const auto start = Clock::now();
    auto s = open_byte_stream(url, 200);
    if (s.ok()) {
      queued.push_back(std::move(s).value());
      continue;
    }
    const long long ms = elapsed_ms(start);
    CHECK(s.error().code == Error::Code::timeout);
    CHECK(s.error().message == url + ": no connection within 200 ms");
    CHECK(ms >= 190);
    CHECK(ms < 1500);
    timed_out = true;
  }
  CHECK(timed_out);
}

TEST_CASE("an unknown host is `not_found`") {
  // .invalid is reserved (RFC 2606): it never resolves.
  auto s = open_byte_stream("tcp://no-such-robot.invalid:8101", 2000);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().code == Error::Code::not_found);
  CHECK(s.error().message.find("no-such-robot.invalid") != std::string::npos);
}

TEST_CASE("malformed tcp URLs are `invalid_argument` naming the URL") {
  const char* bad[] = {"tcp://127.0.0.1", "tcp://127.0.0.1:0", "tcp://:8101", "tcp://127.0.0.1:8101/robot",
                       "tcp://127.0.0.1:8101?nodelay=1", "tcp://127.0.0.1:x"};
  for (const char* url : bad) {
    auto s = open_byte_stream(url, 500);
    REQUIRE_FALSE(s.ok());
    CHECK_MESSAGE(s.error().code == Error::Code::invalid_argument, url);
    CHECK_MESSAGE(s.error().message.find(url) != std::string::npos, s.error().message);
  }
  auto missing_port = open_byte_stream("tcp://127.0.0.1", 500);
  REQUIRE_FALSE(missing_port.ok());
  CHECK(missing_port.error().message.find("missing port") != std::string::npos);
}

TEST_CASE("unknown scheme and bad timeout") {
  auto foo = open_byte_stream("foo://x", 500);
  REQUIRE_FALSE(foo.ok());
  CHECK(foo.error().code == Error::Code::invalid_argument);
  CHECK(foo.error().message == "unknown scheme 'foo' in 'foo://x' (expected tcp:// or serial://)");

  auto no_scheme = open_byte_stream("127.0.0.1:8101", 500);
  REQUIRE_FALSE(no_scheme.ok());
  CHECK(no_scheme.error().code == Error::Code::invalid_argument);

  auto zero = open_byte_stream("tcp://127.0.0.1:8101", 0);
  REQUIRE_FALSE(zero.ok());
  CHECK(zero.error().code == Error::Code::invalid_argument);
}

TEST_CASE("listener: accept timeout, busy port, bad arguments") {
  auto listener = TcpListener::listen("127.0.0.1", 0);
  REQUIRE(listener.ok());
  const int port = (*listener)->port();

  auto start = Clock::now();
  auto none = (*listener)->accept(50);
  REQUIRE(none.ok());
  CHECK(none.value() == nullptr);
  CHECK(elapsed_ms(start) >= 45);

  auto polled = (*listener)->accept(0);
  REQUIRE(polled.ok());
  CHECK(polled.value() == nullptr);

  auto busy = TcpListener::listen("127.0.0.1", port);
  REQUIRE_FALSE(busy.ok());
  CHECK(busy.error().code == Error::Code::refused);
  CHECK(busy.error().message.find(std::to_string(port)) != std::string::npos);
  CHECK(busy.error().message.find("already in use") != std::string::npos);

  auto out_of_range = TcpListener::listen("127.0.0.1", 70000);
  REQUIRE_FALSE(out_of_range.ok());
  CHECK(out_of_range.error().code == Error::Code::invalid_argument);

  auto negative = TcpListener::listen("127.0.0.1", -1);
  REQUIRE_FALSE(negative.ok());
  CHECK(negative.error().code == Error::Code::invalid_argument);

  // 192.0.2.0/24 is TEST-NET-1: never an address of this machine.
  auto foreign = TcpListener::listen("192.0.2.1", 0);
  REQUIRE_FALSE(foreign.ok());
  CHECK(foreign.error().code == Error::Code::not_found);
  CHECK(foreign.error().message.find("192.0.2.1") != std::string::npos);
}

TEST_CASE("listener on all interfaces accepts a loopback client") {
  auto listener = TcpListener::listen("", 0);
  REQUIRE(listener.ok());
  auto client = open_byte_stream(url_for((*listener)->port()), 2000);
  REQUIRE(client.ok());
  auto server = (*listener)->accept(2000);
  REQUIRE(server.ok());
  REQUIRE(server.value() != nullptr);
  const std::vector<std::uint8_t> byte = {0x5A};
  REQUIRE((*client)->write_all(byte).ok());
  std::vector<std::uint8_t> got(1);
  auto n = server.value()->read_some(got, 1000);
  REQUIRE(n.ok());
  CHECK(*n == 1);
  CHECK(got[0] == 0x5A);
}
