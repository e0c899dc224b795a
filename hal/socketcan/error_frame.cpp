#include "socketcan/error_frame.hpp"

#include <linux/can.h>
#include <linux/can/error.h>

namespace p3at::hal::socketcan {
namespace {

void add(std::string& out, const char* what) {
  if (!out.empty()) out += "; ";
  out += what;
}

}  // namespace

ErrorFrameReport decode_error_frame(std::uint32_t can_id, const std::array<std::uint8_t, 8>& data) {
  ErrorFrameReport report;
  const std::uint32_t cls = can_id & CAN_ERR_MASK;
  if ((cls & CAN_ERR_TX_TIMEOUT) != 0) add(report.description, "tx-timeout");
  if ((cls & CAN_ERR_LOSTARB) != 0) add(report.description, "lost-arbitration");
  if ((cls & CAN_ERR_CRTL) != 0) {
    // Order matters: a frame may carry several bits; the most severe state wins.
    const std::uint8_t crtl = data[1];
    if ((crtl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0) {
      report.overflow = true;
      add(report.description, "controller: buffer overflow");
    }
    if ((crtl & CAN_ERR_CRTL_ACTIVE) != 0) {
      report.state = CanBusState::error_active;
      add(report.description, "controller: error-active again");
    }
    if ((crtl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) {
      report.state = CanBusState::error_warning;
      add(report.description, "controller: error-warning");
    }
    if ((crtl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      report.state = CanBusState::error_passive;
      add(report.description, "controller: error-passive");
    }
    if (crtl == 0) add(report.description, "controller: unspecified problem");
  }
  if ((cls & CAN_ERR_PROT) != 0) add(report.description, "protocol violation");
  if ((cls & CAN_ERR_TRX) != 0) add(report.description, "transceiver fault");
  if ((cls & CAN_ERR_ACK) != 0) add(report.description, "no ack");
  if ((cls & CAN_ERR_BUSERROR) != 0) add(report.description, "bus error");
  if ((cls & CAN_ERR_BUSOFF) != 0) {
    report.state = CanBusState::bus_off;
    add(report.description, "bus-off");
  }
  if ((cls & CAN_ERR_RESTARTED) != 0) {
    report.state = CanBusState::error_active;
    add(report.description, "controller restarted");
  }
  if ((cls & CAN_ERR_CNT) != 0) {
    report.has_counters = true;
    report.tx_error_counter = data[6];
    report.rx_error_counter = data[7];
  }
  if (report.description.empty()) add(report.description, "unspecified error");
  return report;
}

}  // namespace p3at::hal::socketcan
