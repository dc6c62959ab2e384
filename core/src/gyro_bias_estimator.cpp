#include "headingd/core/gyro_bias_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

bool RestDetector::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* current_bias, double dt_s) {
  const Vec3& gyro_mean = gyro_mean_.update(gyro_rad_s, dt_s);
  const Vec3& accel_mean = accel_mean_.update(accel_m_s2, dt_s);
  const double gyro_rms = std::sqrt(gyro_deviation2_.update((gyro_rad_s - gyro_mean).squaredNorm(), dt_s));
  const double accel_rms = std::sqrt(accel_deviation2_.update((accel_m_s2 - accel_mean).squaredNorm(), dt_s));
  gyro_floor_.update(gyro_rms, dt_s);
  const double gyro_bound =
      gyro_floor_.threshold(2.5, p_.rest_gyro_threshold_rad_s, p_.rest_gyro_max_threshold_rad_s);
  const bool steady = gyro_rms < gyro_bound && accel_rms < p_.rest_accel_threshold_m_s2 &&
                      // Before the first estimate any rate up to the largest plausible bias
                      // may be the bias.
                      (current_bias ? (gyro_mean - *current_bias).norm() < gyro_bound
                                    : gyro_mean.norm() < p_.bias_max_rad_s);
  rest_time_s_ = steady ? rest_time_s_ + dt_s : 0.0;
  return atRest();
}

const Vec3& GyroBiasEstimator::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s) {
  if (!rest_.update(gyro_rad_s, accel_m_s2, rest_seconds_ > 0.0 ? &bias_ : nullptr, dt_s)) return bias_;
  // A steady rate above the clamp is a turn, not a bias: keep the last good estimate.
  if (gyro_rad_s.norm() > 2.0 * p_.bias_max_rad_s) return bias_;
  rest_seconds_ += dt_s;
  // A plain running mean until one time constant of rest has been seen (the first rest then
  // gives the mean of all its samples rather than a first-sample start), an exponential
  // low-pass (eq. 2.13/2.17) after that, so that the bias can follow temperature drift.
  const double weight = std::max(dt_s / rest_seconds_, 1.0 - alpha_(dt_s));
  const Vec3 updated = bias_ + weight * (gyro_rad_s - bias_);
  if (updated.norm() <= p_.bias_max_rad_s) bias_ = updated;
  return bias_;
}

}  // namespace headingd::core
