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
  std::int64_t kernel_time_ns = 0;  // CLOCK_REALTIME from SO_TIMESTAMPNS; 0 if unknown
};

}  // namespace headingd::can
