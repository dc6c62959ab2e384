#include "headingd/core/accel_prefilter.hpp"

namespace headingd::core {

Vec3 AccelPrefilter::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s) {
  if (time_constant_s_ <= 0.0) return accel_m_s2;
  const Vec3 angle = gyro_rad_s * dt_s;
  const double norm = angle.norm();
  if (norm > 0.0) q_inertial_body_ = (q_inertial_body_ * Quat(Eigen::AngleAxisd(norm, angle / norm))).normalized();
  const Vec3& filtered_inertial = filtered_.update(q_inertial_body_ * accel_m_s2, dt_s);
  return q_inertial_body_.conjugate() * filtered_inertial;
}

void AccelPrefilter::restart() {
  q_inertial_body_ = Quat::Identity();
  filtered_ = LowPass<Vec3>(time_constant_s_);
}

}  // namespace headingd::core
