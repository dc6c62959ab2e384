#pragma once
// The phone grade: a phone's IMU and magnetometer drawn per seed from ranges, not one sensor,
// so a seed sweep is a sweep over phones. The ranges are those of the held-out recordings
// (issue 28): consumer gyros of 0.003-0.02 rad/s white noise per sample at 100 Hz with
// constant biases up to 6 deg/s, a magnetometer at 25-50 Hz repeated between its samples and
// 20-40 ms late against the gyro. Sources of each number in phone_imu.cpp.
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/sim/imu_model.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::sim {

struct DrawRange {
  double lo;
  double hi;
};

// What the phone grade draws from (each a single value for all three axes of a triad, except
// the gyro's constant bias, drawn per axis).
struct PhoneRanges {
  // White noise per sample at 100 Hz, rad/s (a density, so the same density at other rates);
  // log-uniform.
  static constexpr DrawRange kGyroNoiseAt100Hz_rad_s{0.003, 0.02};
  // |constant gyro bias| per axis, rad/s, log-uniform, random sign: 0.05 to 6 deg/s.
  static constexpr DrawRange kGyroBiasMagnitude_rad_s{0.05 * core::kRadPerDeg, 6.0 * core::kRadPerDeg};
  // Accelerometer white-noise density, m/s²/√Hz (100-400 µg/√Hz), log-uniform.
  static constexpr DrawRange kAccelNoiseDensity{100e-6 * 9.80665, 400e-6 * 9.80665};
  // Magnetometer white noise per sample, µT, uniform.
  static constexpr DrawRange kMagNoise_uT{0.4, 1.5};
  static constexpr DrawRange kMagRate_hz{25.0, 50.0};
  static constexpr DrawRange kMagLag_s{0.020, 0.040};
  static constexpr DrawRange kAccelLag_s{0.0, 0.005};
  // Accelerometer full scale, m/s², one of these, each as likely: phones' parts run at ±2 g
  // (the Nexus 5 and the iPhone 4S of the shared recordings: a quarter of a run's samples
  // clipped on one axis with the phone in the hand), ±4 g or ±8 g (the iPhone 5).
  static constexpr double kAccelFullScale_m_s2[] = {2.0 * 9.80665, 4.0 * 9.80665, 8.0 * 9.80665};
};

// One phone: its triads' errors and its sensor timing.
ImuModel drawPhoneImu(double field_strength_uT, Rng& rng);

}  // namespace headingd::sim
