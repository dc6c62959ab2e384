#include "headingd/core/gait_mount_yaw.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace headingd::core {

void GaitMountYawEstimator::update(const Quat& q_nb, const Vec3& accel_m_s2, double dt_s, double gravity_m_s2) {
  // Acceleration in NED (specific force plus gravity), horizontal part, turned into the frame
  // whose x-axis is the sensor's x-axis projected on the horizontal plane.
  const Vec3 accel_n = q_nb * accel_m_s2 + Vec3(0.0, 0.0, gravity_m_s2);
  const Vec3 x_axis_n = q_nb * Vec3::UnitX();
  const double sensor_heading = std::atan2(x_axis_n.y(), x_axis_n.x());
  const double c = std::cos(sensor_heading), s = std::sin(sensor_heading);
  const Eigen::Vector2d horizontal(c * accel_n.x() + s * accel_n.y(), -s * accel_n.x() + c * accel_n.y());
  const Eigen::Vector2d varying = horizontal - mean_.update(horizontal, dt_s);
  sxx_ += dt_s * varying.x() * varying.x();
  syy_ += dt_s * varying.y() * varying.y();
  sxy_ += dt_s * varying.x() * varying.y();
  weight_ += dt_s;
  walking_seconds_ += dt_s;
}

double GaitMountYawEstimator::mountYawRad() const {
  if (!hasEstimate()) return 0.0;
  // Principal axis of [[sxx, sxy], [sxy, syy]]: φ = ½ atan2(2 sxy, sxx - syy), in (-90°, 90°].
  const double forward_in_sensor_frame = 0.5 * std::atan2(2.0 * sxy_, sxx_ - syy_);
  return -forward_in_sensor_frame;
}

double GaitMountYawEstimator::sigmaRad() const {
  if (!hasEstimate()) return std::numeric_limits<double>::infinity();
  const double mean = 0.5 * (sxx_ + syy_) / weight_;
  const double half_diff = 0.5 * std::hypot(sxx_ - syy_, 2.0 * sxy_) / weight_;
  const double major = mean + half_diff, minor = std::max(mean - half_diff, 0.0);
  if (major - minor <= 0.0) return std::numbers::pi / 2.0;  // isotropic: no direction at all
  // Standard error of a principal axis from n independent samples:
  // var(φ) ≈ λ1 λ2 / (n (λ1 - λ2)²). Samples within one step are correlated; we count one
  // independent sample per half second (about one step).
  const double independent = std::max(walking_seconds_ / 0.5, 1.0);
  return std::sqrt(major * minor / independent) / (major - minor);
}

}  // namespace headingd::core
