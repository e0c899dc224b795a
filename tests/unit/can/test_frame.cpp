#include <doctest/doctest.h>

#include <array>
#include <cstdint>

#include "p3at/protocols/can/frame.hpp"

using p3at::can::Frame;

TEST_CASE("make_frame checks id range and payload length") {
  const std::array<std::uint8_t, 3> bytes{1, 2, 3};
  auto ok = p3at::can::make_frame(0x7FF, bytes);
  REQUIRE(ok);
  CHECK(ok->id == 0x7FF);
  CHECK(ok->length == 3);
  CHECK(ok->data[2] == 3);

  auto too_big = p3at::can::make_frame(0x800, bytes);
  REQUIRE_FALSE(too_big);
  CHECK(too_big.error().code == p3at::Error::Code::invalid_argument);
  CHECK(too_big.error().message.find("11 bits") != std::string::npos);

  CHECK(p3at::can::make_frame(0x1FFFFFFF, bytes, true));
  CHECK_FALSE(p3at::can::make_frame(0x20000000, bytes, true));

  const std::array<std::uint8_t, 9> nine{};
  auto long_payload = p3at::can::make_frame(0x100, nine);
  REQUIRE_FALSE(long_payload);
  CHECK(long_payload.error().message.find("9 bytes") != std::string::npos);
}

TEST_CASE("frames compare by their used bytes only") {
  Frame a;
  a.id = 0x123;
  a.length = 2;
  a.data = {1, 2, 99, 99, 0, 0, 0, 0};
  Frame b = a;
  b.data[2] = 7;  // beyond length
  CHECK(a == b);
  b.data[1] = 3;
  CHECK_FALSE(a == b);
  Frame c = a;
  c.extended = true;
  CHECK_FALSE(a == c);
}

TEST_CASE("format_frame writes cansend syntax") {
  const std::array<std::uint8_t, 4> dead{0xDE, 0xAD, 0xBE, 0xEF};
  CHECK(p3at::can::format_frame(*p3at::can::make_frame(0x123, dead)) == "123#DEADBEEF");
  CHECK(p3at::can::format_frame(*p3at::can::make_frame(0x1F334455, dead, true)) == "1F334455#DEADBEEF");
  CHECK(p3at::can::format_frame(*p3at::can::make_frame(0x5, {})) == "005#");
  Frame remote;
  remote.id = 0x123;
  remote.remote = true;
  CHECK(p3at::can::format_frame(remote) == "123#R");
  remote.length = 3;
  CHECK(p3at::can::format_frame(remote) == "123#R3");
}

TEST_CASE("parse_frame reads cansend and candump -L syntax") {
  auto f = p3at::can::parse_frame("5A1#11.2233.44556677.88");
  REQUIRE(f);
  CHECK(f->id == 0x5A1);
  CHECK_FALSE(f->extended);
  CHECK(f->length == 8);
  CHECK(f->data[0] == 0x11);
  CHECK(f->data[7] == 0x88);

  auto ext = p3at::can::parse_frame("1F334455#1122334455667788");
  REQUIRE(ext);
  CHECK(ext->extended);
  CHECK(ext->id == 0x1F334455);

  auto lower = p3at::can::parse_frame("191#0a0b");
  REQUIRE(lower);
  CHECK(lower->data[0] == 0x0A);

  auto empty = p3at::can::parse_frame("5AA#");
  REQUIRE(empty);
  CHECK(empty->length == 0);

  auto rtr = p3at::can::parse_frame("00000123#R3");
  REQUIRE(rtr);
  CHECK(rtr->remote);
  CHECK(rtr->extended);
  CHECK(rtr->length == 3);
}

TEST_CASE("parse_frame round-trips format_frame") {
  for (std::uint32_t id : {0x000u, 0x080u, 0x191u, 0x7FFu}) {
    for (std::uint8_t len = 0; len <= 8; ++len) {
      Frame frame;
      frame.id = id;
      frame.length = len;
      for (std::uint8_t i = 0; i < len; ++i) frame.data[i] = static_cast<std::uint8_t>(id + i * 37u);
      auto back = p3at::can::parse_frame(p3at::can::format_frame(frame));
      REQUIRE(back);
      CHECK(*back == frame);
    }
  }
}

TEST_CASE("parse_frame rejects malformed text with a clear message") {
  for (const char* bad : {"", "123", "12#00", "1234#00", "12G#00", "123#0", "123#GG", "123#000102030405060708",
                          "123##1", "800#00", "20000040#0000000000000000", "123#R9", "123#R12"}) {
    CAPTURE(bad);
    auto r = p3at::can::parse_frame(bad);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == p3at::Error::Code::invalid_argument);
    CHECK(r.error().message.find("invalid CAN frame") != std::string::npos);
  }
}
