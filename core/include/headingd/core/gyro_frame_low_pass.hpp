#pragma once
// Low-pass of a body-frame vector (accelerometer, magnetometer) in a gyro-integrated frame.
//
// For the accelerometer, before the EKF's gravity update. Why: the EKF of Henriksson ch. 3 compares each raw sample
// with gravity. A body that accelerates (a person's steps, a hand moving a device around) adds accelerations that
// average to zero over a few seconds but not over one sample; the R levels of §3.1 only
// trust the sample less. Filtering in the body frame would smear gravity whenever the body
// turns, so the samples are first rotated into a frame that turns with the gyro alone
// (q_I, integrated from the bias-corrected rate and never corrected), low-passed there
// (eq. 2.13, α from eq. 2.17), and rotated back into the current body axes. Gravity is
// constant in that frame up to the slow gyro drift, so it passes; the accelerations of the
// motion are filtered out. The same idea drives VQF's accelerometer correction (Laidig &
// Seel 2023); here its output is simply the measurement a_k of eq. 3.7a.
//
// For the magnetometer, with a short time constant, it takes the white noise out of the field
// (strength and dip tests of §4.2 compare samples with thresholds, and the heading observer
// sees the field) without the lag a body-frame filter would have while the body turns.
//
// Computed the other way round, with the same result: the filter's state is kept in the
// current body axes and turned with each gyro increment (y_b ← r* y_b r), which is the
// low-pass in the gyro frame seen from the body. One rotation per sample instead of
// rotating every sample in and the result back out.
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// How the filter starts: from its first sample (which then weighs exp(-t/τ) in the output),
// or as the running mean of the samples so far until that is the slower of the two (a long
// time constant would otherwise carry a start made in motion for many seconds).
enum class GyroFrameStart { kFirstSample, kRunningMean };

class GyroFrameLowPass {
 public:
  // time_constant_s = 0 turns the filter off: the raw sample goes through (the thesis).
  explicit GyroFrameLowPass(double time_constant_s, GyroFrameStart start = GyroFrameStart::kFirstSample)
      : time_constant_s_(time_constant_s), start_(start), filtered_(time_constant_s) {}

  // Returns the filtered vector in the current body axes.
  Vec3 update(const Vec3& gyro_rad_s, const Vec3& body_vector, double dt_s) {
    return update(gyroIncrement(gyro_rad_s, dt_s), body_vector, dt_s);
  }
  // The same with the sample's rotation already computed (gyroIncrement).
  Vec3 update(const Quat& increment, const Vec3& body_vector, double dt_s) {
    advance(increment);
    return add(body_vector, dt_s);
  }
  // The two halves, for a sensor that has no sample at every gyro sample: the frame must
  // follow every rotation, the filter takes the samples there are.
  void advance(const Quat& increment);
  Vec3 add(const Vec3& body_vector, double dt_s);

  // Forget the history (after a gap: the gyro frame is not valid across it).
  void restart();

 private:
  double time_constant_s_;
  GyroFrameStart start_;
  LowPass<Vec3> filtered_;    // in the current body axes
  double seconds_ = 0.0;      // of samples taken since the start (kRunningMean)
  bool handed_over_ = false;  // the running mean has given way to the low-pass (kRunningMean)
};

}  // namespace headingd::core
