#include "headingd/core/gait_mount_yaw.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::core {

void GaitMountYawEstimator::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s) {
  q_start_sensor_ = (q_start_sensor_ * gyroIncrement(gyro_rad_s, dt_s)).normalized();
  const Vec3 force = q_start_sensor_ * accel_m_s2;
  force_sum_ += force;
  force_moment_sum_ += force * force.transpose();
  x_axis_sum_ += q_start_sensor_ * Vec3::UnitX();
  window_seconds_ += dt_s;
  ++window_samples_;
  if (window_seconds_ >= window_s_) closeWindow();
}

void GaitMountYawEstimator::closeWindow() {
  const double n = static_cast<double>(window_samples_);
  const Vec3 mean = force_sum_ / n;
  const Vec3 up = mean.normalized();  // the specific force of gravity points up
  const Mat3 covariance = force_moment_sum_ / n - mean * mean.transpose();
  // The sensor heading frame of the window: forward = the mean x-axis on the horizontal
  // plane, right = down × forward (x, y, z = forward, right, down as NED's north, east, down).
  const Vec3 x_axis = x_axis_sum_ - x_axis_sum_.dot(up) * up;
  const double seconds = window_seconds_;
  restart();
  if (!(mean.norm() > 0.0) || !(x_axis.norm() > 1e-3 * n)) return;  // x-axis near vertical: no heading frame
  const Vec3 forward = x_axis.normalized();
  const Vec3 right = forward.cross(up);
  const double xx = seconds * forward.dot(covariance * forward), yy = seconds * right.dot(covariance * right),
               xy = seconds * forward.dot(covariance * right);
  sxx_ += xx;
  syy_ += yy;
  sxy_ += xy;
  walking_seconds_ += seconds;
  block_sxx_ += xx;
  block_syy_ += yy;
  block_sxy_ += xy;
  block_seconds_ += seconds;
  if (block_seconds_ >= kBlockSeconds) {
    block_axes_.add(std::atan2(2.0 * block_sxy_, block_sxx_ - block_syy_));  // 2φ of this block
    block_sxx_ = block_syy_ = block_sxy_ = block_seconds_ = 0.0;
  }
}

void GaitMountYawEstimator::restart() {
  q_start_sensor_ = Quat::Identity();
  force_sum_.setZero();
  force_moment_sum_.setZero();
  x_axis_sum_.setZero();
  window_seconds_ = 0.0;
  window_samples_ = 0;
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
  if (block_axes_.count() < 3) return 10.0 * kRadPerDeg;
  return 0.5 * block_axes_.standardError();  // halved: the blocks' angles are doubled
}

}  // namespace headingd::core
