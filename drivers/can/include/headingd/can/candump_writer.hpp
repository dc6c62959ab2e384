#pragma once
// IMU samples -> `candump -l` log through the DBC encoder: each sample becomes the frames of
// one epoch (magnetometer-only messages first, so a receiver that releases an epoch on gyro
// and accel already has the magnetometer), spaced like frames on a real bus.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::can {

struct CandumpWriteOptions {
  std::string interface = "can0";
  std::int64_t start_time_ns = 1'700'000'000'000'000'000;  // added to the samples' t_ns (CLOCK_REALTIME)
  std::int64_t frame_spacing_ns = 200'000;  // between frames of one epoch (an 8-byte frame at 500 kbit/s is ~0.25 ms)
  int mag_every = 1;                        // magnetometer frames on every n-th epoch only (a slower magnetometer)
};

struct CandumpWriteStats {
  std::uint64_t epochs = 0;
  std::uint64_t frames = 0;
  std::uint64_t clamped_values = 0;           // values outside a signal's range, written as its nearest end
  std::uint64_t epochs_without_mag_data = 0;  // samples with has_mag = false: no magnetometer frame
};

CandumpWriteStats writeCandumpLog(const std::vector<core::ImuSample>& samples, const ImuFrameCodec& codec,
                                  const CandumpWriteOptions& options, std::ostream& out);

}  // namespace headingd::can
