#include "headingd/core/gyro_frame_low_pass.hpp"

namespace headingd::core {

void GyroFrameLowPass::advance(const Quat& increment) {
  if (time_constant_s_ > 0.0) q_inertial_body_ = (q_inertial_body_ * increment).normalized();
}

Vec3 GyroFrameLowPass::add(const Vec3& body_vector, double dt_s) {
  if (time_constant_s_ <= 0.0) return body_vector;
  const Vec3& filtered_inertial = filtered_.update(q_inertial_body_ * body_vector, dt_s);
  return q_inertial_body_.conjugate() * filtered_inertial;
}

void GyroFrameLowPass::restart() {
  q_inertial_body_ = Quat::Identity();
  filtered_ = LowPass<Vec3>(time_constant_s_);
}

}  // namespace headingd::core
