#include "headingd/core/epoch_compass.hpp"

#include <cmath>

#include "headingd/core/mag_heading_observer.hpp"

namespace headingd::core {

void EpochCompass::add(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT, double dt_s) {
  q_start_sensor_ = (q_start_sensor_ * gyroIncrement(gyro_rad_s, dt_s)).normalized();
  accel_sum_ += q_start_sensor_ * accel_m_s2;
  x_axis_sum_ += q_start_sensor_ * Vec3::UnitX();
  ++accel_count_;
  if (mag_uT != nullptr) {
    mag_sum_ += q_start_sensor_ * *mag_uT;
    ++mag_count_;
  }
}

std::optional<double> EpochCompass::takeHeading(std::size_t min_samples, double min_horizontal_fraction) {
  std::optional<double> heading;
  if (accel_count_ >= min_samples && accel_count_ > 0 && mag_count_ > 0) {
    const Quat q_sensor_start = q_start_sensor_.conjugate();
    const Vec3 accel = q_sensor_start * (accel_sum_ / static_cast<double>(accel_count_));
    const Vec3 mag = q_sensor_start * (mag_sum_ / static_cast<double>(mag_count_));
    if (accel.norm() > 0.0) {
      // The specific force of a body that does not accelerate points up (-down): the
      // attitude that takes it onto NED up has the sensor's roll and pitch (and an arbitrary
      // heading, which measuredHeading accounts for).
      const Quat q_tilt = Quat::FromTwoVectors(-accel, Vec3::UnitZ());
      const MagHeadingMeasurement m = measureMagHeading(q_tilt, mag, min_horizontal_fraction);
      if (m.valid) {
        // From the heading at the end to the interval's mean heading: the angle about down
        // from the end's x-axis to the mean x-axis, both on the horizontal plane.
        const Vec3 down = -accel.normalized();
        const Vec3 mean_x = q_sensor_start * x_axis_sum_;
        const Vec3 end_x_h = Vec3::UnitX() - down.x() * down, mean_x_h = mean_x - mean_x.dot(down) * down;
        const double to_mean = std::atan2(down.dot(end_x_h.cross(mean_x_h)), end_x_h.dot(mean_x_h));
        heading = wrapAngle(measuredHeading(q_tilt, m) + to_mean);
      }
    }
  }
  restart();
  return heading;
}

void EpochCompass::restart() {
  q_start_sensor_ = Quat::Identity();
  accel_sum_.setZero();
  x_axis_sum_.setZero();
  mag_sum_.setZero();
  accel_count_ = 0;
  mag_count_ = 0;
}

}  // namespace headingd::core
