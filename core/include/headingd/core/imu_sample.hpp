#pragma once
// One 9-axis IMU sample in SI units (gyro rad/s, specific force m/s², field µT) in the
// IMU's own axes, stamped with monotonic nanoseconds.
#include <cstdint>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct ImuSample {
  std::int64_t t_ns = 0;
  Vec3 gyro_rad_s = Vec3::Zero();
  Vec3 accel_m_s2 = Vec3::Zero();
  Vec3 mag_uT = Vec3::Zero();
  bool has_mag = true;  // a magnetometer slower than the gyro leaves some samples without
};

}  // namespace headingd::core
