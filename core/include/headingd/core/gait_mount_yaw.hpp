#pragma once
// How the IMU is turned about the body's vertical axis, from the gait (issue 4, item 5).
//
// While a person walks, each step accelerates and brakes the trunk along its forward axis
// (the forward-backward component at the step rate), while the sideways sway is smaller
// and at half the step rate. Over many steps the horizontal acceleration, expressed in the
// sensor's own heading frame, therefore spreads most along the body's forward axis: its
// principal axis gives the mounting yaw without any reference to north. (Henriksson ch. 5
// notes that GPS course minus magnetic heading cannot separate mounting yaw from
// declination; this estimate can, because it does not involve north at all.)
//
// Convention: the sensor axes are the body axes turned by mount_yaw about the body's down
// axis (clockwise seen from above), so the sensor's x-axis points at body heading +
// mount_yaw, and the body's forward axis lies at -mount_yaw in the sensor's heading frame.
// The principal axis has a 180° ambiguity; we take the one within ±90° of the sensor's
// x-axis (an IMU is not worn backwards), stated here because it is an assumption.
#include "headingd/core/circular_mean.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class GaitMountYawEstimator {
 public:
  // high_pass_time_constant_s: the mean horizontal acceleration (speeding up, slowing
  // down, a tilt error) is removed with a low-pass of this time constant.
  explicit GaitMountYawEstimator(double high_pass_time_constant_s = 2.0) : mean_(high_pass_time_constant_s) {}

  // One sample while walking: the attitude estimate (sensor to NED) and the specific force.
  void update(const Quat& q_nb, const Vec3& accel_m_s2, double dt_s, double gravity_m_s2);

  bool hasEstimate() const { return walking_seconds_ >= 10.0; }
  double mountYawRad() const;   // 0 before there is an estimate
  // Uncertainty of mountYawRad (∞ before there is an estimate), by batch means: the walk is
  // cut into blocks of kBlockSeconds, each block gives its own principal axis, and the
  // spread of those over √(blocks) is the standard error. Step samples are strongly
  // correlated (a gait is nearly periodic), so treating them as independent would be wrong
  // either way; blocks of many steps are close to independent.
  double sigmaRad() const;
  double walkingSeconds() const { return walking_seconds_; }

 private:
  LowPass<Eigen::Vector2d> mean_;
  // Second moments of the high-passed horizontal acceleration in the sensor heading frame.
  double sxx_ = 0.0, syy_ = 0.0, sxy_ = 0.0, weight_ = 0.0;
  static constexpr double kBlockSeconds = 10.0;
  double block_sxx_ = 0.0, block_syy_ = 0.0, block_sxy_ = 0.0, block_seconds_ = 0.0;
  CircularMean block_axes_;  // doubled angles (an axis is defined modulo 180°)
  double walking_seconds_ = 0.0;
};

}  // namespace headingd::core
