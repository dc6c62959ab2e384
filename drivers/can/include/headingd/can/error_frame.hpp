#pragma once
// Kernel CAN error frames (linux/can/error.h): the class bits in the id and the detail bytes,
// turned into counters a STATUS message can carry.
#include <cstdint>

#include "headingd/can/can_frame.hpp"

namespace headingd::can {

struct BusErrorCounters {
  std::uint64_t error_frames = 0;
  std::uint64_t tx_timeouts = 0;
  std::uint64_t lost_arbitration = 0;
  std::uint64_t controller_problems = 0;
  std::uint64_t controller_rx_overflow = 0;  // frames lost in the controller
  std::uint64_t controller_tx_overflow = 0;
  std::uint64_t error_warning = 0;  // rx or tx error counter reached 96
  std::uint64_t error_passive = 0;  // ... reached 128
  std::uint64_t back_to_error_active = 0;
  std::uint64_t protocol_violations = 0;
  std::uint64_t transceiver_problems = 0;
  std::uint64_t no_ack = 0;
  std::uint64_t bus_off = 0;
  std::uint64_t bus_errors = 0;
  std::uint64_t controller_restarted = 0;
  std::uint8_t last_tx_error_count = 0;  // data[6]/[7] when the driver reports them
  std::uint8_t last_rx_error_count = 0;
};

// Adds one error frame to the counters; frames without error_frame set are ignored.
void countErrorFrame(const CanFrame& frame, BusErrorCounters& counters);

// Short text of the classes set in an error frame ("bus-off, controller"), for logs.
const char* errorClassSummary(std::uint32_t error_class_bits, char* buffer, std::size_t size);

}  // namespace headingd::can
