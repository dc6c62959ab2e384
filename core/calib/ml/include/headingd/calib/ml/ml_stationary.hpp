#pragma once
// Kok & Schön (2016) Algorithm 1 step 1a: gyroscope bias and the noise covariances Σω, Σa,
// Σm from a batch of stationary samples (the mean and the covariance of each triad).
#include <cstddef>
#include <span>

#include "headingd/core/imu_sample.hpp"

namespace headingd::calib {

struct StationaryStatistics {
  std::size_t samples = 0;                          // used (finite gyro and accelerometer)
  std::size_t mag_samples = 0;                      // of those, with a finite magnetometer reading
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();  // mean gyro: the body is at rest
  core::Mat3 gyro_cov = core::Mat3::Zero();         // (rad/s)²
  core::Vec3 accel_mean_m_s2 = core::Vec3::Zero();
  core::Mat3 accel_cov = core::Mat3::Zero();  // (m/s²)²
  core::Vec3 mag_mean_uT = core::Vec3::Zero();
  core::Mat3 mag_cov_uT2 = core::Mat3::Zero();  // µT²
};

// Statistics of `stationary`. Samples with a non-finite value are left out (and not
// counted in `samples`). Throws CalibrationError when fewer than 3 usable samples remain
// (a covariance needs them).
StationaryStatistics stationaryStatistics(std::span<const core::ImuSample> stationary);

}  // namespace headingd::calib
