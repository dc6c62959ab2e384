#pragma once
// The bridge between CAN frames and IMU axes: the [can] configuration resolved against its
// DBC database. Decoding turns one frame into the axis values it carries (SI units, signs
// applied); encoding does the inverse for capture writers and the candump generator.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "headingd/can/can_config.hpp"
#include "headingd/can/can_frame.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::can {

// Axis index: gyro x,y,z = 0..2, accel x,y,z = 3..5, mag x,y,z = 6..8.
inline constexpr int kAxisCount = 9;
inline constexpr std::uint16_t kGyroAxes = 0x007;
inline constexpr std::uint16_t kAccelAxes = 0x038;
inline constexpr std::uint16_t kMagAxes = 0x1C0;

struct AxisBinding {
  int axis = 0;
  DbcSignal signal;
  double scale_to_si = 1.0;  // sign * unit factor: SI value = decoded DBC value * scale_to_si
};

struct MessageBinding {
  std::string name;
  std::uint32_t id = 0;  // as in the DBC (for J1939 with its priority and source address)
  bool extended = false;
  std::uint32_t match_mask = 0;  // frame matches when (frame.id & mask) == (id & mask)
  unsigned dlc = 8;
  std::vector<AxisBinding> axes;
  bool has_sequence = false;
  DbcSignal sequence;
  std::uint16_t axis_mask = 0;  // the axes this message carries
};

// A kernel CAN_RAW_FILTER entry in the driver's own terms (no Linux headers here).
struct IdFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;  // over the identifier bits
  bool extended = false;
};

struct DecodedFrame {
  std::uint16_t axis_mask = 0;
  std::array<double, kAxisCount> values{};  // SI, valid where axis_mask has the bit
  std::uint16_t full_scale_mask = 0;        // axes read at their signal's full scale (atFullScale)
  bool has_sequence = false;
  std::uint64_t sequence = 0;
  const MessageBinding* message = nullptr;
};

enum class DecodeStatus { decoded, unknown_id, wrong_length, remote_frame, error_frame };

class ImuFrameCodec {
 public:
  // Resolves every signal reference; throws ConfigError naming the configuration key's line,
  // the reference and what was expected (unknown message/signal, unknown unit, counters that
  // disagree in width, a J1939 setting on standard ids, ...).
  ImuFrameCodec(const CanConfig& config, const DbcDatabase& dbc);

  DecodeStatus decode(const CanFrame& frame, DecodedFrame& out) const;

  // Frames carrying `sample` (body axes, SI) with the epoch counter `sequence`; messages that
  // carry only magnetometer axes are left out when `include_mag` is false. Returns the number
  // of signal values that had to be clamped to the DBC's range (0 normally).
  int encode(const core::ImuSample& sample, std::uint64_t sequence, bool include_mag,
             std::vector<CanFrame>& frames) const;

  std::vector<IdFilter> kernelFilters() const;
  const std::vector<MessageBinding>& messages() const { return messages_; }
  bool hasMag() const { return has_mag_; }
  unsigned sequenceBits() const { return sequence_bits_; }  // 0 without counters

 private:
  std::vector<MessageBinding> messages_;
  bool has_mag_ = false;
  unsigned sequence_bits_ = 0;
};

// Reads the configuration file and its DBC file and resolves them; throws ConfigError (a
// broken DBC file is reported as an error of the `dbc` key, with the DBC's own file:line).
struct CanSetup {
  CanConfig config;
  DbcDatabase dbc;
};
CanSetup loadCanSetup(const std::string& config_path);

}  // namespace headingd::can
