#include "headingd/core/accel_disturbance.hpp"

namespace headingd::core {

double AccelDisturbanceLevel::update(const Vec3& accel_m_s2, double sample_period_s) {
  const double alpha = alpha_(sample_period_s);
  const double deviation = accel_m_s2.norm() - gravity_m_s2_;
  d_ = alpha * d_ + (1.0 - alpha) * deviation * deviation;
  return d_;
}

const char* motionLevelName(MotionLevel level) {
  switch (level) {
    case MotionLevel::kStanding: return "standing";
    case MotionLevel::kWalking: return "walking";
    case MotionLevel::kRunning: return "running";
  }
  return "unknown";
}

MotionLevel MotionLevelSelector::update(double d) {
  // One step per sample is enough: d_k is low-passed, so it never jumps two bands at once
  // by more than a sample or two.
  switch (level_) {
    case MotionLevel::kStanding:
      if (d > p_.disturbance_up_to_walking) level_ = MotionLevel::kWalking;
      break;
    case MotionLevel::kWalking:
      if (d > p_.disturbance_up_to_running) {
        level_ = MotionLevel::kRunning;
      } else if (d < p_.disturbance_down_to_standing) {
        level_ = MotionLevel::kStanding;
      }
      break;
    case MotionLevel::kRunning:
      if (d < p_.disturbance_down_to_walking) level_ = MotionLevel::kWalking;
      break;
  }
  return level_;
}

}  // namespace headingd::core
