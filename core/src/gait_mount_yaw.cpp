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
  const double xx = dt_s * varying.x() * varying.x(), yy = dt_s * varying.y() * varying.y(),
               xy = dt_s * varying.x() * varying.y();
  sxx_ += xx;
  syy_ += yy;
  sxy_ += xy;
  weight_ += dt_s;
  walking_seconds_ += dt_s;
  block_sxx_ += xx;
  block_syy_ += yy;
  block_sxy_ += xy;
  block_seconds_ += dt_s;
  if (block_seconds_ >= kBlockSeconds) {
    block_axes_.add(std::atan2(2.0 * block_sxy_, block_sxx_ - block_syy_));  // 2φ of this block
    block_sxx_ = block_syy_ = block_sxy_ = block_seconds_ = 0.0;
  }
}

double GaitMountYawEstimator::mountYawRad() const {
  if (!hasEstimate()) return 0.0;
  // Principal axis of [[sxx, sxy], [sxy, syy]]: φ = ½ atan2(2 sxy, sxx - syy), in (-90°, 90°].
  const double forward_in_sensor_frame = 0.5 * std::atan2(2.0 * sxy_, sxx_ - syy_);
  return -forward_in_sensor_frame;
}

double GaitMountYawEstimator::sigmaRad() const {
  if (!hasEstimate()) return std::numeric_limits<double>::infinity();
  // Fewer than three blocks say little about their spread: stay at a cautious 10°.
  if (block_axes_.count() < 3) return 10.0 * std::numbers::pi / 180.0;
  return 0.5 * block_axes_.standardError();  // halved: the blocks' angles are doubled
}

}  // namespace headingd::core
