#include "headingd/calib/ml/ml_parameters.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace headingd::calib {

namespace {

void packCholesky(const core::Mat3& cov, const char* name, double* p) {
  const Eigen::LLT<core::Mat3> llt(0.5 * (cov + cov.transpose()));
  if (llt.info() != Eigen::Success || !cov.allFinite()) {
    throw std::invalid_argument(std::string(name) + " covariance is not positive definite");
  }
  const core::Mat3 L = llt.matrixL();
  p[0] = std::log(L(0, 0));
  p[1] = L(1, 0) / L(1, 1);
  p[2] = std::log(L(1, 1));
  p[3] = L(2, 0) / L(2, 2);
  p[4] = L(2, 1) / L(2, 2);
  p[5] = std::log(L(2, 2));
}

}  // namespace

MlParameters packParameters(const MlParameterValues& v) {
  MlParameters theta{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) theta[ml_index::kD + 3 * r + c] = v.D(r, c);
  }
  for (int i = 0; i < 3; ++i) {
    theta[ml_index::kOffset + i] = v.offset(i);
    theta[ml_index::kGyroBias + i] = v.gyro_bias_rad_s(i) / kGyroBiasUnit_rad_s;
  }
  theta[ml_index::kDip] = v.dip_rad;
  packCholesky(v.gyro_cov, "gyro", theta.data() + ml_index::kGyroCov);
  packCholesky(v.accel_cov, "accelerometer", theta.data() + ml_index::kAccelCov);
  packCholesky(v.mag_cov, "magnetometer", theta.data() + ml_index::kMagCov);
  return theta;
}

MlParameterValues unpackParameters(const MlParameters& theta) {
  const MlModel<double> m = modelFromParameters<double>(theta.data());
  MlParameterValues v;
  v.D = m.D;
  v.offset = m.offset;
  v.dip_rad = theta[ml_index::kDip];
  v.gyro_bias_rad_s = m.gyro_bias;
  v.gyro_cov = m.gyro_cov;
  v.accel_cov = m.accel_cov;
  v.mag_cov = m.mag_cov;
  return v;
}

}  // namespace headingd::calib
