#pragma once
// The inertial-only EKF of Kok & Schön (2016) §6.2: the same multiplicative EKF as the ML
// predictor (ml_ekf.hpp), with the gyroscope and the accelerometer only. The magnetometer is
// not calibrated yet, so heading is left to drift; the inclination, all that eq. 27 needs,
// comes from the accelerometer.
#include <vector>

#include "headingd/calib/ml/ml_data.hpp"

namespace headingd::calib {

struct InclinationEkfSettings {
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  core::Mat3 gyro_cov = core::Mat3::Identity() * 1e-4;   // (rad/s)²
  core::Mat3 accel_cov = core::Mat3::Identity() * 1e-2;  // (m/s²)²
};

// The vertical (NED down) in body axes at each sample, v_b,t = R_bn,t (0, 0, 1)ᵀ (K&S eq.
// 26a; they point z up, we down, so v·m_n = sin δ). A sample whose update fails (a
// covariance no longer positive definite) keeps the predicted attitude.
std::vector<core::Vec3> verticalInBody(const MlData& data, const InclinationEkfSettings& settings);

}  // namespace headingd::calib
