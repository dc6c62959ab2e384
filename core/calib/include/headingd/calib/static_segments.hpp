#pragma once
// Static segments of a recording: stretches where the sensor lies still, found by variance
// tests on the gyroscope and the accelerometer over a sliding window (Henriksson 2013 §2.8
// places the IMU on its sides and at rest; Kok & Schön 2016 Algorithm 1 starts from a
// stationary batch). The thresholds are relative to the recording's own noise floor (the
// quietest windows), so the same settings work for a consumer and a better IMU.
#include <cstddef>
#include <span>
#include <vector>

#include "headingd/core/imu_sample.hpp"

namespace headingd::calib {

struct StaticDetectionOptions {
  double window_s = 0.5;                // centred window of the variance tests
  double min_duration_s = 2.0;          // shorter still stretches are not segments
  double noise_floor_factor = 2.5;      // still: window σ below this × the floor (per sensor)
  double min_gyro_sigma_rad_s = 0.003;  // floors of the thresholds (an ideal sensor has σ 0)
  double min_accel_sigma_m_s2 = 0.01;
  double max_gyro_mean_rad_s = 0.1;  // a slow steady turn has a small σ too; biases are below this
};

struct StaticSegment {
  std::size_t begin = 0;  // sample indices, [begin, end)
  std::size_t end = 0;
  core::Vec3 gyro_mean = core::Vec3::Zero();
  core::Vec3 accel_mean = core::Vec3::Zero();
  core::Vec3 mag_mean = core::Vec3::Zero();
  core::Vec3 gyro_sigma = core::Vec3::Zero();  // sample standard deviations
  core::Vec3 accel_sigma = core::Vec3::Zero();
  core::Vec3 mag_sigma = core::Vec3::Zero();
  std::size_t size() const { return end - begin; }
};

// `rate_hz` is the sample rate (from the timestamps if 0). Samples with non-finite values
// end a segment. Returns the segments in time order.
std::vector<StaticSegment> findStaticSegments(std::span<const core::ImuSample> samples,
                                              const StaticDetectionOptions& options = {}, double rate_hz = 0.0);

// Mean and standard deviation of the samples in [begin, end).
StaticSegment summarise(std::span<const core::ImuSample> samples, std::size_t begin, std::size_t end);

// Sample rate from the median timestamp step; throws CalibrationError if it cannot be told.
double sampleRateHz(std::span<const core::ImuSample> samples);

}  // namespace headingd::calib
