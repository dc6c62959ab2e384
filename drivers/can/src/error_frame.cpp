#include "headingd/can/error_frame.hpp"

#include <linux/can/error.h>

#include <cstdio>
#include <cstring>

namespace headingd::can {

void countErrorFrame(const CanFrame& f, BusErrorCounters& c) {
  if (!f.error_frame) return;
  ++c.error_frames;
  const std::uint32_t cls = f.id;
  if ((cls & CAN_ERR_TX_TIMEOUT) != 0) ++c.tx_timeouts;
  if ((cls & CAN_ERR_LOSTARB) != 0) ++c.lost_arbitration;
  if ((cls & CAN_ERR_CRTL) != 0) {
    ++c.controller_problems;
    const std::uint8_t d1 = f.data[1];
    if ((d1 & CAN_ERR_CRTL_RX_OVERFLOW) != 0) ++c.controller_rx_overflow;
    if ((d1 & CAN_ERR_CRTL_TX_OVERFLOW) != 0) ++c.controller_tx_overflow;
    if ((d1 & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) ++c.error_warning;
    if ((d1 & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) ++c.error_passive;
    if ((d1 & CAN_ERR_CRTL_ACTIVE) != 0) ++c.back_to_error_active;
  }
  if ((cls & CAN_ERR_PROT) != 0) ++c.protocol_violations;
  if ((cls & CAN_ERR_TRX) != 0) ++c.transceiver_problems;
  if ((cls & CAN_ERR_ACK) != 0) ++c.no_ack;
  if ((cls & CAN_ERR_BUSOFF) != 0) ++c.bus_off;
  if ((cls & CAN_ERR_BUSERROR) != 0) ++c.bus_errors;
  if ((cls & CAN_ERR_RESTARTED) != 0) ++c.controller_restarted;
  if ((cls & 0x200u) != 0) {  // CAN_ERR_CNT (kernel 5.19+): data[6] tx, data[7] rx error counters
    c.last_tx_error_count = f.data[6];
    c.last_rx_error_count = f.data[7];
  }
}

const char* errorClassSummary(std::uint32_t cls, char* buffer, std::size_t size) {
  static constexpr struct {
    std::uint32_t bit;
    const char* name;
  } kNames[] = {
      {CAN_ERR_TX_TIMEOUT, "tx-timeout"}, {CAN_ERR_LOSTARB, "lost-arbitration"}, {CAN_ERR_CRTL, "controller"},
      {CAN_ERR_PROT, "protocol"},         {CAN_ERR_TRX, "transceiver"},          {CAN_ERR_ACK, "no-ack"},
      {CAN_ERR_BUSOFF, "bus-off"},        {CAN_ERR_BUSERROR, "bus-error"},       {CAN_ERR_RESTARTED, "restarted"}};
  if (size == 0) return buffer;
  buffer[0] = '\0';
  std::size_t used = 0;
  for (const auto& n : kNames) {
    if ((cls & n.bit) == 0) continue;
    const int w = std::snprintf(buffer + used, size - used, "%s%s", used == 0 ? "" : ", ", n.name);
    if (w < 0 || static_cast<std::size_t>(w) >= size - used) break;
    used += static_cast<std::size_t>(w);
  }
  return buffer;
}

}  // namespace headingd::can
