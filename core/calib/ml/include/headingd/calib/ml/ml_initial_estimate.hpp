#pragma once
// Kok & Schön (2016) Algorithm 1, step 1: the initial estimate θ̂0 the maximum-likelihood
// refinement starts from.
//   (a) gyro bias and Σω, Σa, Σm from a stationary segment (ml_stationary.hpp);
//   (b) ellipsoid fit, D̃0 and o0 (§6.1, ellipsoid_fit.hpp);
//   (c) misalignment R_D and dip (§6.2, eqs. 26-28) with the inertial-only EKF
//       (inclination_ekf.hpp, misalignment.hpp): D̂0 = D̃0 R_D.
#include <cstddef>
#include <optional>
#include <span>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/calib/ml/ml_parameters.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::calib {

struct MlInitialOptions {
  // The local field's norm: from the WMM at the place, or given by the user. D is
  // dimensionless, the offset in µT, for y_m = D m_b + o with |m_b| this norm.
  double field_norm_uT = 50.0;
  // Where the sensor lies still (K&S §8: the first 100 samples).
  std::size_t stationary_begin = 0;
  std::size_t stationary_count = 100;
  // g for the accelerometer model (eq. 16); 0 takes the stationary mean's norm, which also
  // absorbs a common scale error of the accelerometer.
  double gravity_m_s2 = 0.0;
  std::size_t initial_average_samples = 10;
  double ellipsoid_min_coverage = 0.25;
  double ellipsoid_sphere_weight = 1e-2;  // EllipsoidFitOptions::sphere_weight
  // Floors for the σ taken from the stationary covariances: a quantised or ideal sensor can
  // give a zero variance, which no likelihood can start from.
  double min_gyro_sigma_rad_s = 1e-4;
  double min_accel_sigma_m_s2 = 1e-3;
  double min_mag_sigma_uT = 0.02;
  // The dip's sign from the place (WMM) or the hemisphere: picks between eq. 27's mirror
  // minima, and the ML step refuses the mirror (dip_sign.hpp). kUnknown: the best minimum.
  DipSign expected_dip_sign = DipSign::kUnknown;
  // The dip itself from the WMM at the place and date, when known: the ML step's second start
  // (ml_calibration.hpp, MlCalibrationOptions::max_restarts).
  std::optional<double> expected_dip_rad;
};

struct MlInitialEstimate {
  core::Mat3 D = core::Mat3::Identity();      // D̂0 = D̃0 R_D (eq. 28a)
  core::Vec3 offset_uT = core::Vec3::Zero();  // o0 (eq. 24c)
  double dip_rad = 0.0;                       // from m̂_z,0 (eq. 28b)
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  core::Mat3 gyro_cov = core::Mat3::Identity();     // (rad/s)²
  core::Mat3 accel_cov = core::Mat3::Identity();    // (m/s²)²
  core::Mat3 mag_cov_uT2 = core::Mat3::Identity();  // µT²
  // Pieces, for the report.
  core::Mat3 ellipsoid_D = core::Mat3::Identity();   // D̃0
  core::Mat3 misalignment = core::Mat3::Identity();  // R_D
  double misalignment_rms = 0.0;                     // of eq. 27, in field units
  int misalignment_minima = 0;                       // distinct minima of eq. 27 found
  bool misalignment_sign_chosen = false;             // the expected dip sign passed over a lower minimum
  double ellipsoid_coverage = 0.0;
  double ellipsoid_residual_rms_uT = 0.0;
  double ellipsoid_condition_number = 0.0;
  double gravity_m_s2 = 9.81;
  double field_norm_uT = 50.0;
};

// Throws CalibrationError when the stationary segment is outside the data or too short, or
// the ellipsoid fit fails (too little rotation).
MlInitialEstimate estimateInitialParameters(std::span<const core::ImuSample> samples, const MlInitialOptions& options);

// θ in the ML problem's units (field normalised), with the σ floors applied.
MlParameterValues initialParameterValues(const MlInitialEstimate& initial, const MlInitialOptions& options);

}  // namespace headingd::calib
