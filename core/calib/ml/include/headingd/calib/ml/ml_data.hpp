#pragma once
// The measurements of the maximum-likelihood problem (Kok & Schön 2016 eq. 1), in the units
// the problem is posed in: the magnetometer divided by the local field's norm (K&S §4 take
// the field as a unit vector), gyro in rad/s, accelerometer in m/s².
#include <cstddef>
#include <span>
#include <vector>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::calib {

struct MlSample {
  double dt_s = 0.0;                           // since the previous sample (0 for the first and after a gap)
  core::Vec3 gyro_rad_s = core::Vec3::Zero();  // the rate over (t - dt, t]
  double gyro_noise_dt2_s2 = 0.0;              // Σ dt_i² of the gyro samples in this step (dt² for one)
  core::Vec3 accel_m_s2 = core::Vec3::Zero();
  core::Vec3 mag_unit = core::Vec3::Zero();  // µT / field norm
  bool has_mag = false;
  // After decimation (MlDataOptions::decimation): accel_m_s2 and mag_unit are means over
  // the group's samples (those with a magnetometer for mag), each seen through the body's
  // rotation from its time to this one; these are the mean of those rotations and the counts.
  core::Mat3 accel_mean_rotation = core::Mat3::Identity();
  core::Mat3 mag_mean_rotation = core::Mat3::Identity();
  double accel_count = 1.0;
  double mag_count = 1.0;
};

struct MlData {
  std::vector<MlSample> samples;
  double gravity_m_s2 = 9.81;
  double field_norm_uT = 1.0;
  // The EKF starts from the mean accelerometer and magnetometer of the first few samples
  // (K&S record at rest first).
  std::size_t initial_average_samples = 10;
  // The dip's sign known from the place (dip_sign.hpp): the likelihood refuses the mirror.
  DipSign expected_dip_sign = DipSign::kUnknown;
  // Bad input, counted so that the caller can report it, never silently dropped.
  std::size_t dropped_non_finite = 0;  // samples with a non-finite gyro or accelerometer
  std::size_t mag_non_finite = 0;      // samples kept without their magnetometer
  std::size_t time_gaps = 0;           // dt ≤ 0 or above max_dt_s: no prediction across it
};

struct MlDataOptions {
  double field_norm_uT = 50.0;
  double gravity_m_s2 = 9.81;
  double max_dt_s = 0.5;  // a longer step is a gap in the recording, not one sample
  std::size_t initial_average_samples = 10;
  DipSign expected_dip_sign = DipSign::kUnknown;
  // Groups of `decimation` samples become one EKF step: the gyro pre-integrated into one
  // rotation increment (exact for the rotation; the noise as Σ dt_i² Σω), the accelerometer
  // and magnetometer averaged, each reading i being modelled through the gyro's rotation R_i
  // from its time to the group's end (the models are linear in R_bn, so the mean is D M R_bn
  // m_n + o with M = mean R_i, its noise Σ/k; the gyro bias within a group is neglected:
  // 1°/s over 0.1 s is 0.1°). 1: every sample. The EKF's cost grows with the number of steps,
  // so this is how minutes of 100 Hz data become affordable without discarding readings.
  // The first `initial_average_samples` steps start the EKF: at rest, any.
  std::size_t decimation = 1;
};

// Throws std::invalid_argument for a non-positive field norm or gravity.
MlData prepareMlData(std::span<const core::ImuSample> samples, const MlDataOptions& options);

}  // namespace headingd::calib
