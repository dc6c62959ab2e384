#pragma once
// The measurements of the maximum-likelihood problem (Kok & Schön 2016 eq. 1), in the units
// the problem is posed in: the magnetometer divided by the local field's norm (K&S §4 take
// the field as a unit vector), gyro in rad/s, accelerometer in m/s².
#include <cstddef>
#include <span>
#include <vector>

#include "headingd/core/imu_sample.hpp"

namespace headingd::calib {

struct MlSample {
  double dt_s = 0.0;  // since the previous sample (0 for the first and after a gap)
  core::Vec3 gyro_rad_s = core::Vec3::Zero();  // the rate over (t - dt, t]
  core::Vec3 accel_m_s2 = core::Vec3::Zero();
  core::Vec3 mag_unit = core::Vec3::Zero();    // µT / field norm
  bool has_mag = false;
};

struct MlData {
  std::vector<MlSample> samples;
  double gravity_m_s2 = 9.81;
  double field_norm_uT = 1.0;
  // The EKF starts from the mean accelerometer and magnetometer of the first few samples
  // (K&S record at rest first).
  std::size_t initial_average_samples = 10;
  // Bad input, counted (DESIGN.md: never silently dropped).
  std::size_t dropped_non_finite = 0;  // samples with a non-finite gyro or accelerometer
  std::size_t mag_non_finite = 0;      // samples kept without their magnetometer
  std::size_t time_gaps = 0;           // dt ≤ 0 or above max_dt_s: no prediction across it
};

struct MlDataOptions {
  double field_norm_uT = 50.0;
  double gravity_m_s2 = 9.81;
  double max_dt_s = 0.5;  // a longer step is a gap in the recording, not one sample
  std::size_t initial_average_samples = 10;
};

// Throws std::invalid_argument for a non-positive field norm or gravity.
MlData prepareMlData(std::span<const core::ImuSample> samples, const MlDataOptions& options);

}  // namespace headingd::calib
