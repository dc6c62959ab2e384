#pragma once
// The parameter vector θ of Kok & Schön (2016) §5.3 (eq. 17) as the optimiser sees it, 34
// numbers as in the paper:
//   [0, 9)   D, row-major
//   [9, 12)  o, in units of the field norm
//   12       dip δ (eq. 8b), rad
//   [13, 16) gyro bias δω, in units of kGyroBiasUnit_rad_s
//   [16, 22) Σω, [22, 28) Σa, [28, 34) Σm: Cholesky factors (K&S §5.3), each as
//            (a0, c10, a1, c20, c21, a2) with L_ii = exp(a_i), L_ij = exp(a_i)·c_ij
// The log diagonal keeps every Σ positive definite without constraints; scaling the
// off-diagonal by its row's diagonal and the bias by a typical size keeps all entries of θ
// near unit size, which the quasi-Newton method's first steps need.
#include <array>
#include <cmath>

#include "headingd/calib/ml/ml_ekf.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::calib {

inline constexpr int kMlParameterCount = 34;
inline constexpr double kGyroBiasUnit_rad_s = 0.01;

namespace ml_index {
inline constexpr int kD = 0;
inline constexpr int kOffset = 9;
inline constexpr int kDip = 12;
inline constexpr int kGyroBias = 13;
inline constexpr int kGyroCov = 16;
inline constexpr int kAccelCov = 22;
inline constexpr int kMagCov = 28;
}  // namespace ml_index

using MlParameters = std::array<double, kMlParameterCount>;

template <typename T>
Mat3T<T> choleskyFactorFromParameters(const T* p) {
  using std::exp;
  const T l0 = exp(p[0]), l1 = exp(p[2]), l2 = exp(p[5]);
  Mat3T<T> L = Mat3T<T>::Zero();
  L(0, 0) = l0;
  L(1, 0) = l1 * p[1];
  L(1, 1) = l1;
  L(2, 0) = l2 * p[3];
  L(2, 1) = l2 * p[4];
  L(2, 2) = l2;
  return L;
}

template <typename T>
MlModel<T> modelFromParameters(const T* theta) {
  MlModel<T> m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m.D(r, c) = theta[ml_index::kD + 3 * r + c];
  }
  for (int i = 0; i < 3; ++i) {
    m.offset(i) = theta[ml_index::kOffset + i];
    m.gyro_bias(i) = theta[ml_index::kGyroBias + i] * T(kGyroBiasUnit_rad_s);
  }
  m.field_n = fieldFromDip<T>(theta[ml_index::kDip]);
  const Mat3T<T> Lw = choleskyFactorFromParameters<T>(theta + ml_index::kGyroCov);
  const Mat3T<T> La = choleskyFactorFromParameters<T>(theta + ml_index::kAccelCov);
  const Mat3T<T> Lm = choleskyFactorFromParameters<T>(theta + ml_index::kMagCov);
  m.gyro_cov = Lw * Lw.transpose();
  m.accel_cov = La * La.transpose();
  m.mag_cov = Lm * Lm.transpose();
  return m;
}

// What θ stands for, in physical terms (D dimensionless, offset in field units).
struct MlParameterValues {
  core::Mat3 D = core::Mat3::Identity();
  core::Vec3 offset = core::Vec3::Zero();  // field units
  double dip_rad = 0.0;
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  core::Mat3 gyro_cov = core::Mat3::Identity();   // (rad/s)²
  core::Mat3 accel_cov = core::Mat3::Identity();  // (m/s²)²
  core::Mat3 mag_cov = core::Mat3::Identity();    // field units²
};

// Throws std::invalid_argument if a covariance is not positive definite.
MlParameters packParameters(const MlParameterValues& values);
MlParameterValues unpackParameters(const MlParameters& theta);

}  // namespace headingd::calib
