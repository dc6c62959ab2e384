#include "headingd/core/accel_prefilter.hpp"

namespace headingd::core {

Vec3 AccelPrefilter::update(const Quat& increment, const Vec3& accel_m_s2, double dt_s) {
  if (time_constant_s_ <= 0.0) return accel_m_s2;
  q_inertial_body_ = (q_inertial_body_ * increment).normalized();
  const Vec3& filtered_inertial = filtered_.update(q_inertial_body_ * accel_m_s2, dt_s);
  return q_inertial_body_.conjugate() * filtered_inertial;
}

void AccelPrefilter::restart() {
  q_inertial_body_ = Quat::Identity();
  filtered_ = LowPass<Vec3>(time_constant_s_);
}

}  // namespace headingd::core
