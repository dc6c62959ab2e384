#pragma once
// One classic CAN frame as the driver sees it, independent of the kernel's struct can_frame
// so that the pure parts (DBC decoding, epoch assembly, candump logs) build and test anywhere.
#include <array>
#include <cstdint>

namespace headingd::can {

inline constexpr std::uint32_t kStandardIdMask = 0x7FFu;
inline constexpr std::uint32_t kExtendedIdMask = 0x1FFFFFFFu;
inline constexpr std::uint8_t kClassicMaxLen = 8;

struct CanFrame {
  std::uint32_t id = 0;      // 11-bit (standard) or 29-bit (extended) identifier, no flag bits
  bool extended = false;     // 29-bit identifier (J1939 uses these)
  bool remote = false;       // remote transmission request: carries no data
  bool error_frame = false;  // kernel error report; `id` holds the CAN_ERR_* class bits
  std::uint8_t len = 0;      // data length in bytes, 0..8 (classic CAN: DLC == length)
  std::array<std::uint8_t, 8> data{};
  // The frame's time on its stream's time axis, the one the epoch assembler stamps the samples
  // with: CLOCK_MONOTONIC for a live bus (the live source moves the kernel's receive timestamp
  // there), the log's clock for a candump log, the estimator's for a recording's frames. The
  // receiver, which knows only the kernel's wall-clock stamp, hands that over beside the frame
  // (socketcan_receiver.hpp) and leaves this 0.
  std::int64_t t_ns = 0;
};

}  // namespace headingd::can
