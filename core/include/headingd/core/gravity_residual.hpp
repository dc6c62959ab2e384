#pragma once
// How disturbed the accelerometer's gravity measurement still is after the gyro-frame
// low-pass (gyro_frame_low_pass.hpp), and the measurement noise R_k of the EKF's gravity
// update (Henriksson eq. 3.6-3.7) that follows from it.
//
// The thesis (§3.1) steps R between three levels by d_k, the low-passed (|a| - g)² of the
// raw samples. But the EKF is fed the low-passed vector, not the raw samples: shaking at a
// few Hz makes d_k huge although the low-pass has taken nearly all of it out, and the long
// time constant of the top level then turns any gyro bias or noise into degrees of tilt
// (6-30 deg of inclination in 60 s of simulated shaking; a slow hand-held motion
// whose accelerations pass the low-pass needs the large R, and gets it). What is left in the
// measurement y is measured directly: y wanders about its own slower low-pass z (the same
// gyro-frame filter applied once more) as far as the accelerations the first low-pass did
// not remove; gravity and a tilt error do not move it. So
//   d = low-pass of |y - z|²,   R_k = (σ_a² + κ d) I,
// σ_a the measurement noise of a quiet accelerometer (accel_noise_m_s2), κ
// (accel_residual_gain) how much a wandering measurement counts beyond its spread: the
// wander is correlated over seconds, not white as the EKF assumes.
#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class GravityResidual {
 public:
  // slow_time_constant_s: of the second gyro-frame low-pass (z); spread_time_constant_s: of
  // the low-pass of |y - z|².
  GravityResidual(double slow_time_constant_s, double spread_time_constant_s)
      : slow_(slow_time_constant_s), spread_(spread_time_constant_s) {}

  // y: the low-passed gravity measurement of this sample; increment: the sample's gyro
  // rotation. Returns d in (m/s²)².
  double update(const Quat& increment, const Vec3& y, double dt_s) {
    const Vec3 z = slow_.update(increment, y, dt_s);
    return spread_.update((y - z).squaredNorm(), dt_s);
  }
  double value() const { return spread_.value(); }
  // Forget the history (after a gap, as the low-pass before it).
  void restart(double slow_time_constant_s, double spread_time_constant_s) {
    *this = GravityResidual(slow_time_constant_s, spread_time_constant_s);
  }

 private:
  GyroFrameLowPass slow_;
  LowPass<double> spread_;
};

// R_k's standard deviation (m/s²) for a residual disturbance d.
inline double gravityMeasurementNoise(double quiet_noise_m_s2, double residual_gain, double d) {
  return std::sqrt(quiet_noise_m_s2 * quiet_noise_m_s2 + residual_gain * d);
}

}  // namespace headingd::core
