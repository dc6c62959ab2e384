#pragma once
// How the IMU is turned about the body's vertical axis, from the gait.
//
// While a person walks, each step accelerates and brakes the trunk along its forward axis
// (the forward-backward component at the step rate), while the sideways sway is smaller
// and at half the step rate. Over many steps the horizontal acceleration, expressed in the
// sensor's own heading frame, therefore spreads most along the body's forward axis: its
// principal axis gives the mounting yaw without any reference to north. (Henriksson ch. 5
// notes that GPS course minus magnetic heading cannot separate mounting yaw from
// declination; this estimate can, because it does not involve north at all.)
//
// Where "horizontal" comes from: not from the attitude estimator. Its tilt follows the
// gait's own accelerations a little (the accelerometer update sees them), with a lag, so
// its error is correlated with the steps and leaks the 2.8 m/s² vertical bounce and the
// forward swing into the other horizontal axis: on the simulated walk that biased the
// mounting yaw by -0.13 … -0.24° even with an ideal IMU (with the true attitude: < 0.02°).
// Instead the specific force is carried in a gyro frame over a short window (the bias-
// corrected gyro drifts a few hundredths of a degree in it), and the window's mean specific
// force is the vertical: over whole strides the gait's accelerations average out, what is
// left is gravity. The second moments about that mean are the high-passed accelerations.
//
// Convention: the sensor axes are the body axes turned by mount_yaw about the body's down
// axis (clockwise seen from above), so the sensor's x-axis points at body heading +
// mount_yaw, and the body's forward axis lies at -mount_yaw in the sensor's heading frame.
// The principal axis has a 180° ambiguity; we take the one within ±90° of the sensor's
// x-axis (an IMU is not worn backwards), stated here because it is an assumption.
#include <cstddef>

#include "headingd/core/circular_mean.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class GaitMountYawEstimator {
 public:
  // window_s: the length of one gyro-frame window (several strides, so that the mean
  // specific force is the vertical; short, so that the gyro does not drift in it).
  explicit GaitMountYawEstimator(double window_s = 4.0) : window_s_(window_s) {}

  // One sample while walking: the gyro with its bias removed and the specific force, both
  // in sensor axes.
  void update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s);
  // Not walking, or a gap in the samples: the window so far is dropped (its frame and its
  // mean would mix two different things).
  void restart();

  bool hasEstimate() const { return walking_seconds_ >= 10.0; }
  double mountYawRad() const;  // 0 before there is an estimate
  // Uncertainty of mountYawRad (∞ before there is an estimate), by batch means: the walk is
  // cut into blocks of kBlockSeconds, each block gives its own principal axis, and the
  // spread of those over √(blocks) is the standard error. Step samples are strongly
  // correlated (a gait is nearly periodic), so treating them as independent would be wrong
  // either way; blocks of many steps are close to independent.
  double sigmaRad() const;
  double walkingSeconds() const { return walking_seconds_; }

 private:
  void closeWindow();

  double window_s_;
  // The current window, in the gyro frame of its first sample.
  Quat q_start_sensor_ = Quat::Identity();
  Vec3 force_sum_ = Vec3::Zero();
  Mat3 force_moment_sum_ = Mat3::Zero();
  Vec3 x_axis_sum_ = Vec3::Zero();
  double window_seconds_ = 0.0;
  std::size_t window_samples_ = 0;
  // Second moments (times seconds) of the horizontal acceleration in the sensor heading frame.
  double sxx_ = 0.0, syy_ = 0.0, sxy_ = 0.0;
  static constexpr double kBlockSeconds = 10.0;
  double block_sxx_ = 0.0, block_syy_ = 0.0, block_sxy_ = 0.0, block_seconds_ = 0.0;
  CircularMean block_axes_;  // doubled angles (an axis is defined modulo 180°)
  double walking_seconds_ = 0.0;
};

}  // namespace headingd::core
