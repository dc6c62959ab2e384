#include "headingd/core/zero_rate_model.hpp"

namespace headingd::core {

Linearised<3> ZeroRateModel::linearise(const NavigationState& x, const Vec3& gyro_rad_s) const {
  Linearised<3> l;
  l.residual = gyro_rad_s - x.gyro_bias_rad_s;
  l.jacobian.block<3, 3>(0, error_state::kGyroBias).setIdentity();
  l.noise_covariance = noise_sigma_rad_s * noise_sigma_rad_s * Mat3::Identity();
  return l;
}

}  // namespace headingd::core
