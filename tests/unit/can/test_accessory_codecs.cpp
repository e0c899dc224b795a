#include <doctest/doctest.h>

#include <cmath>

#include "p3at/protocols/can/accessories.hpp"

namespace can = p3at::can;

namespace {

can::Frame frame_of(const char* text) {
  auto f = can::parse_frame(text);
  REQUIRE(f);
  return *f;
}

}  // namespace

TEST_CASE("gyro TPDO1 golden vectors") {
  can::GyroSample s;
  s.yaw_rate_radps = 1.0;  // 1,000,000 µrad/s = 0x000F4240
  s.temperature_c = 30.0;  // 3000 = 0x0BB8
  s.counter = 7;
  CHECK(can::format_frame(can::encode_gyro_pdo(0x10, s)) == "190#40420F00B80B0700");

  s.yaw_rate_radps = -0.5;  // -500,000 = 0xFFF85EE0
  s.temperature_c = -5.25;  // -525 = 0xFDF3
  s.counter = 255;
  s.fault = true;
  CHECK(can::format_frame(can::encode_gyro_pdo(0x10, s)) == "190#E05EF8FFF3FDFF01");

  auto d = can::decode_gyro_pdo(frame_of("190#E05EF8FFF3FDFF01"));
  REQUIRE(d);
  CHECK(d->yaw_rate_radps == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(d->temperature_c == doctest::Approx(-5.25));
  CHECK(d->counter == 255);
  CHECK(d->fault);
  CHECK_FALSE(d->saturated);
}

TEST_CASE("gyro TPDO1 round trip keeps 1 µrad/s and 0.01 °C") {
  for (double rate : {0.0, 1e-6, -1e-6, 0.123456, -3.3, 8.7}) {
    can::GyroSample s;
    s.yaw_rate_radps = rate;
    s.temperature_c = 41.37;
    s.counter = 42;
    auto d = can::decode_gyro_pdo(can::encode_gyro_pdo(0x10, s));
    REQUIRE(d);
    CHECK(std::fabs(d->yaw_rate_radps - rate) <= 0.5e-6 + 1e-12);
    CHECK(d->temperature_c == doctest::Approx(41.37));
    CHECK(d->counter == 42);
  }
}

TEST_CASE("gyro TPDO1 clips out-of-range values and marks them") {
  can::GyroSample s;
  s.yaw_rate_radps = 1e6;  // far beyond s32 µrad/s
  auto d = can::decode_gyro_pdo(can::encode_gyro_pdo(0x10, s));
  REQUIRE(d);
  CHECK(d->saturated);
  CHECK(d->yaw_rate_radps == doctest::Approx(2147.483647));
  s.yaw_rate_radps = std::nan("");
  d = can::decode_gyro_pdo(can::encode_gyro_pdo(0x10, s));
  REQUIRE(d);
  CHECK(d->saturated);
  CHECK(d->yaw_rate_radps == 0.0);
  s = {};
  s.has_temperature = false;
  d = can::decode_gyro_pdo(can::encode_gyro_pdo(0x10, s));
  REQUIRE(d);
  CHECK_FALSE(d->has_temperature);
}

TEST_CASE("gyro TPDO1 decode errors") {
  auto short_frame = can::decode_gyro_pdo(frame_of("190#40420F00B80B07"));
  REQUIRE_FALSE(short_frame);
  CHECK(short_frame.error().message.find("length 7 (expected 8)") != std::string::npos);
  CHECK_FALSE(can::decode_gyro_pdo(frame_of("290#40420F00B80B0700")));
}

TEST_CASE("safety TPDO1 golden vectors and check byte") {
  can::SafetyState s;
  s.estop_pressed = true;
  s.counter = 5;
  CHECK(can::format_frame(can::encode_safety_pdo(0x11, s)) == "191#010005FB");  // FF^01^00^05
  CHECK(can::format_frame(can::encode_safety_pdo(0x11, can::SafetyState{})) == "191#000000FF");
  s = {};
  s.bumpers = 0x21;  // front segment 0, rear segment 1
  s.counter = 0x10;
  CHECK(can::format_frame(can::encode_safety_pdo(0x11, s)) == "191#002110CE");  // FF^00^21^10

  auto d = can::decode_safety_pdo(frame_of("191#010005FB"));
  REQUIRE(d);
  CHECK(d->estop_pressed);
  CHECK_FALSE(d->fault);
  CHECK(d->bumpers == 0);
  CHECK(d->counter == 5);
  CHECK_FALSE(d->clear());
  auto clear = can::decode_safety_pdo(frame_of("191#000000FF"));
  REQUIRE(clear);
  CHECK(clear->clear());
}

TEST_CASE("safety TPDO1 rejects what it cannot trust") {
  auto zero = can::decode_safety_pdo(frame_of("191#00000000"));  // all-zero frame
  REQUIRE_FALSE(zero);
  CHECK(zero.error().message.find("check byte") != std::string::npos);
  CHECK_FALSE(can::decode_safety_pdo(frame_of("191#010005FA")));  // one bit off
  auto unknown = can::decode_safety_pdo(frame_of("191#040000FB"));  // flag bit 2, valid check
  REQUIRE_FALSE(unknown);
  CHECK(unknown.error().message.find("unknown flag") != std::string::npos);
  CHECK_FALSE(can::decode_safety_pdo(frame_of("191#010005")));
  CHECK_FALSE(can::decode_safety_pdo(frame_of("711#010005FB")));
}
