#include "headingd/calib/ml/ml_stationary.hpp"

#include <string>

#include "headingd/calib/calibration_error.hpp"

namespace headingd::calib {

namespace {

struct MeanCov {
  core::Vec3 sum = core::Vec3::Zero();
  core::Mat3 sum_outer = core::Mat3::Zero();
  std::size_t n = 0;
  core::Vec3 origin = core::Vec3::Zero();  // first value: sums around it avoid cancellation

  void add(const core::Vec3& v) {
    if (n == 0) origin = v;
    const core::Vec3 d = v - origin;
    sum += d;
    sum_outer += d * d.transpose();
    ++n;
  }
  core::Vec3 mean() const { return origin + sum / static_cast<double>(n); }
  core::Mat3 cov() const {  // unbiased (n - 1)
    const core::Vec3 m = sum / static_cast<double>(n);
    return (sum_outer - static_cast<double>(n) * m * m.transpose()) / static_cast<double>(n - 1);
  }
};

}  // namespace

StationaryStatistics stationaryStatistics(std::span<const core::ImuSample> stationary) {
  MeanCov gyro, accel, mag;
  for (const core::ImuSample& s : stationary) {
    if (!s.gyro_rad_s.allFinite() || !s.accel_m_s2.allFinite()) continue;
    gyro.add(s.gyro_rad_s);
    accel.add(s.accel_m_s2);
    if (s.has_mag && s.mag_uT.allFinite()) mag.add(s.mag_uT);
  }
  if (gyro.n < 3) {
    throw CalibrationError("stationary segment has " + std::to_string(gyro.n) +
                           " usable samples; at least 3 are needed for a covariance");
  }
  StationaryStatistics out;
  out.samples = gyro.n;
  out.mag_samples = mag.n;
  out.gyro_bias_rad_s = gyro.mean();
  out.gyro_cov = gyro.cov();
  out.accel_mean_m_s2 = accel.mean();
  out.accel_cov = accel.cov();
  if (mag.n >= 3) {
    out.mag_mean_uT = mag.mean();
    out.mag_cov_uT2 = mag.cov();
  }
  return out;
}

}  // namespace headingd::calib
