#include "headingd/core/gyro_frame_low_pass.hpp"

namespace headingd::core {

void GyroFrameLowPass::advance(const Quat& increment) {
  // The gyro frame's q_IB becomes q_IB ⊗ r, so a vector fixed in it, seen in body axes,
  // becomes r* ⊗ y_b ⊗ r. (r is a unit quaternion to rounding: no renormalisation needed.)
  if (time_constant_s_ > 0.0 && filtered_.initialised()) filtered_.reset(increment.conjugate() * filtered_.value());
}

Vec3 GyroFrameLowPass::add(const Vec3& body_vector, double dt_s) {
  if (time_constant_s_ <= 0.0) return body_vector;
  return filtered_.update(body_vector, dt_s);
}

void GyroFrameLowPass::restart() { filtered_ = LowPass<Vec3>(time_constant_s_); }

}  // namespace headingd::core
