#include "headingd/core/imu_calibration.hpp"

#include <cmath>
#include <stdexcept>

namespace headingd::core {

const char* fieldNormSourceName(FieldNormSource s) {
  switch (s) {
    case FieldNormSource::kWmm: return "wmm";
    case FieldNormSource::kArgument: return "argument";
    case FieldNormSource::kData: return "data";
  }
  return "data";
}

ImuCorrection::ImuCorrection(const ImuCalibration& c) {
  const auto inverseScale = [](const Vec3& scale, const char* what) {
    if (!scale.allFinite() || scale.cwiseAbs().minCoeff() < 1e-6) {
      throw std::invalid_argument(std::string(what) + " scale must be finite and non-zero");
    }
    return Vec3(scale.cwiseInverse());
  };
  if (!c.gyro.bias_rad_s.allFinite() || !c.accel.bias_m_s2.allFinite() || !c.mag.offset_uT.allFinite() ||
      !c.mag.D.allFinite()) {
    throw std::invalid_argument("calibration values must be finite");
  }
  // Singular or nearly so (relative to its size): the correction would amplify noise
  // without bound.
  const double size = c.mag.D.norm();
  if (!(std::abs(c.mag.D.determinant()) > 1e-9 * size * size * size)) {
    throw std::invalid_argument("magnetometer D must be invertible");
  }
  gyro_bias_ = c.gyro.bias_rad_s;
  gyro_inverse_scale_ = inverseScale(c.gyro.scale, "gyroscope");
  accel_bias_ = c.accel.bias_m_s2;
  accel_inverse_scale_ = inverseScale(c.accel.scale, "accelerometer");
  d_inverse_ = c.mag.D.inverse();
  mag_offset_uT_ = c.mag.offset_uT;
}

ImuSample ImuCorrection::apply(const ImuSample& s) const {
  ImuSample out = s;
  out.gyro_rad_s = gyro_inverse_scale_.cwiseProduct(s.gyro_rad_s - gyro_bias_);    // eq. 2.41 solved for ω
  out.accel_m_s2 = accel_inverse_scale_.cwiseProduct(s.accel_m_s2 - accel_bias_);  // eq. 2.40 solved for a_p
  if (s.has_mag) out.mag_uT = magnetometer(s.mag_uT);                              // K&S eq. 8 solved for m_b
  return out;
}

}  // namespace headingd::core
