#include <doctest/doctest.h>

#include "p3at/protocols/can/canopen.hpp"

namespace can = p3at::can;

namespace {

can::Frame frame_of(const char* text) {
  auto f = can::parse_frame(text);
  REQUIRE(f);
  return *f;
}

}  // namespace

TEST_CASE("classify follows the predefined connection set") {
  CHECK(can::classify(frame_of("000#0100")).kind == can::MessageKind::nmt);
  CHECK(can::classify(frame_of("080#")).kind == can::MessageKind::sync);
  auto emcy = can::classify(frame_of("091#0000000000000000"));
  CHECK(emcy.kind == can::MessageKind::emcy);
  CHECK(emcy.node_id == 0x11);
  auto pdo = can::classify(frame_of("190#00"));
  CHECK(pdo.kind == can::MessageKind::tpdo1);
  CHECK(pdo.node_id == 0x10);
  auto hb = can::classify(frame_of("77F#05"));
  CHECK(hb.kind == can::MessageKind::heartbeat);
  CHECK(hb.node_id == 127);
  // Node 0 is not a node, other function codes are not ours, extended ids never are.
  CHECK(can::classify(frame_of("180#00")).kind == can::MessageKind::other);
  CHECK(can::classify(frame_of("700#00")).kind == can::MessageKind::other);
  CHECK(can::classify(frame_of("211#00")).kind == can::MessageKind::other);
  CHECK(can::classify(frame_of("00000191#00")).kind == can::MessageKind::other);
  CHECK(can::classify(frame_of("191#R")).kind == can::MessageKind::other);
}

TEST_CASE("NMT golden vectors and decode errors") {
  auto start_all = can::encode_nmt(can::NmtCommand::start, 0);
  REQUIRE(start_all);
  CHECK(can::format_frame(*start_all) == "000#0100");
  auto reset_gyro = can::encode_nmt(can::NmtCommand::reset_node, 0x10);
  REQUIRE(reset_gyro);
  CHECK(can::format_frame(*reset_gyro) == "000#8110");
  CHECK_FALSE(can::encode_nmt(can::NmtCommand::start, 128));

  auto stop = can::decode_nmt(frame_of("000#0211"));
  REQUIRE(stop);
  CHECK(stop->command == can::NmtCommand::stop);
  CHECK(stop->node_id == 0x11);

  auto wrong_len = can::decode_nmt(frame_of("000#01"));
  REQUIRE_FALSE(wrong_len);
  CHECK(wrong_len.error().message.find("length 1 (expected 2)") != std::string::npos);
  CHECK_FALSE(can::decode_nmt(frame_of("000#0300")));  // unknown command specifier
  CHECK_FALSE(can::decode_nmt(frame_of("000#0180")));  // node 128
  CHECK_FALSE(can::decode_nmt(frame_of("001#0100")));  // not COB-ID 0
}

TEST_CASE("heartbeat golden vectors and decode errors") {
  CHECK(can::format_frame(can::encode_heartbeat(0x11, can::NmtState::operational)) == "711#05");
  CHECK(can::format_frame(can::encode_heartbeat(0x10, can::NmtState::boot_up)) == "710#00");
  CHECK(can::format_frame(can::encode_heartbeat(0x10, can::NmtState::pre_operational)) == "710#7F");
  for (const char* text : {"711#00", "711#04", "711#05", "711#7F"}) {
    auto state = can::decode_heartbeat(frame_of(text));
    REQUIRE(state);
    CHECK(can::format_frame(can::encode_heartbeat(0x11, *state)) == text);
  }
  CHECK_FALSE(can::decode_heartbeat(frame_of("711#85")));  // toggle bit set: node guarding, not heartbeat
  CHECK_FALSE(can::decode_heartbeat(frame_of("711#06")));
  CHECK_FALSE(can::decode_heartbeat(frame_of("711#0500")));
  CHECK_FALSE(can::decode_heartbeat(frame_of("711#")));
  CHECK_FALSE(can::decode_heartbeat(frame_of("191#05")));
}

TEST_CASE("EMCY golden vector, round trip and decode errors") {
  can::Emergency e;
  e.error_code = can::emcy_code::kEstopCircuit;
  e.error_register = can::error_register::kManufacturer;
  e.vendor = {1, 2, 3, 4, 5};
  const can::Frame f = can::encode_emcy(0x11, e);
  CHECK(can::format_frame(f) == "091#01FF800102030405");
  auto back = can::decode_emcy(f);
  REQUIRE(back);
  CHECK(back->error_code == 0xFF01);
  CHECK(back->error_register == 0x80);
  CHECK(back->vendor[4] == 5);
  CHECK_FALSE(can::decode_emcy(frame_of("091#01FF80")));
  CHECK_FALSE(can::decode_emcy(frame_of("080#0000000000000000")));  // SYNC, not EMCY
}

TEST_CASE("EMCY codes have readable descriptions") {
  CHECK(std::string(can::describe_emcy_code(0x0000)) == "error reset");
  CHECK(std::string(can::describe_emcy_code(0x4210)) == "temperature");
  CHECK(std::string(can::describe_emcy_code(0x5000)) == "device hardware");
  CHECK(std::string(can::describe_emcy_code(0xFF01)) == "e-stop circuit fault");
  CHECK(std::string(can::describe_emcy_code(0xFF77)) == "device specific");
  CHECK(std::string(can::describe_emcy_code(0xA000)) == "unknown error");
}
