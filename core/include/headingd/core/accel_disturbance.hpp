#pragma once
// How disturbed the accelerometer is (Henriksson §3.1) and the R level chosen from it.
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// d_k = α d_{k-1} + (1-α)(|a_k| - |g|)², Henriksson eq. 3.1 / 3.4, α from eq. 2.17.
class AccelDisturbanceLevel {
 public:
  AccelDisturbanceLevel(double gravity_m_s2, double time_constant_s)
      : gravity_m_s2_(gravity_m_s2), alpha_(time_constant_s) {}
  double update(const Vec3& accel_m_s2, double sample_period_s);
  double value() const { return d_; }

 private:
  double gravity_m_s2_;
  LowPassAlpha alpha_;
  double d_ = 0.0;  // starts undisturbed, as a person standing still
};

enum class MotionLevel { kStanding = 0, kWalking = 1, kRunning = 2 };

const char* motionLevelName(MotionLevel level);

// Chooses among three R levels from d_k with hysteresis (Henriksson §3.1, thresholds §6.2):
// the threshold to step up is above the one to step back down.
class MotionLevelSelector {
 public:
  explicit MotionLevelSelector(const EstimatorParams& p) : p_(p) {}
  MotionLevel update(double disturbance);
  MotionLevel level() const { return level_; }

 private:
  EstimatorParams p_;  // a copy: the owner may be copied or moved (gyro_bias_estimator.hpp)
  MotionLevel level_ = MotionLevel::kStanding;
};

}  // namespace headingd::core
