#include "headingd/core/gyro_frame_low_pass.hpp"

namespace headingd::core {

void GyroFrameLowPass::advance(const Quat& increment) {
  // The gyro frame's q_IB becomes q_IB ⊗ r, so a vector fixed in it, seen in body axes,
  // becomes r* ⊗ y_b ⊗ r. (r is a unit quaternion to rounding: no renormalisation needed.)
  if (time_constant_s_ > 0.0 && filtered_.initialised()) filtered_.reset(increment.conjugate() * filtered_.value());
}

Vec3 GyroFrameLowPass::add(const Vec3& body_vector, double dt_s) {
  if (time_constant_s_ <= 0.0) return body_vector;
  if (start_ == GyroFrameStart::kRunningMean && filtered_.initialised() && !handed_over_) {
    seconds_ += dt_s;
    const double mean_gain = dt_s / seconds_;
    if (mean_gain > 1.0 - lowPassAlpha(dt_s, time_constant_s_)) {
      filtered_.reset(filtered_.value() + mean_gain * (body_vector - filtered_.value()));
      return filtered_.value();
    }
    // The mean's gain only falls from here (by about one time constant of samples), so the
    // low-pass keeps the filter until a restart.
    handed_over_ = true;
    return filtered_.update(body_vector, dt_s);
  }
  seconds_ = dt_s;
  return filtered_.update(body_vector, dt_s);
}

void GyroFrameLowPass::restart() {
  filtered_ = LowPass<Vec3>(time_constant_s_);
  seconds_ = 0.0;
  handed_over_ = false;
}

}  // namespace headingd::core
