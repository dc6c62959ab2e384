#pragma once
// The quaternion EKF of Henriksson (2013) ch. 3, Algorithm 2: the state is q_nb as a
// 4-vector (w, x, y, z); the gyroscope predicts, the accelerometer's view of gravity updates.
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class AttitudeEkf {
 public:
  // Henriksson Algorithm 2 initialises q = (1,0,0,0), P = 1000·I; the estimator instead
  // starts from the first sample's tilt and heading (see Estimator), with a P that says so.
  AttitudeEkf();

  // Prediction, eqs. 3.2-3.3: q ← F q, P ← F P Fᵀ + Q with Q from the gyro white noise
  // mapped through Ξ(q) (Q = (dt/2)² Ξ Σ_ω Ξᵀ).
  void predict(const Vec3& gyro_rad_s, double dt_s, double gyro_noise_rad_s) {
    predict(gyroIncrement(gyro_rad_s, dt_s), dt_s, gyro_noise_rad_s);
  }
  // The same with the sample's rotation already computed (gyroIncrement).
  void predict(const Quat& increment, double dt_s, double gyro_noise_rad_s);

  // Measurement update with the accelerometer, eqs. 3.5-3.7, then normalisation, eq. 3.8.
  // The model is h(q) = M(q) f_n with f_n = (0, 0, -g) the specific force at rest in NED.
  // Eq. 3.7a as printed uses H_k q̂ for the prediction; for the quadratic h that equals
  // 2 h(q̂), so we use the EKF form of eq. 2.9a, h(q̂).
  void updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2);

  // Replaces the attitude (back-tracking of §3.1, heading corrections of ch. 4). The
  // covariance is kept: the replacement is a better estimate of the same state.
  void setAttitude(const Quat& q_nb);

  // Turns the attitude about NED down by angle_rad: the magnetometer observer's correction
  // (Henriksson eq. 4.2), a few 1e-4 rad per sample. Below 0.01 rad P is not carried: P only
  // describes tilt (keepHeadingOutOfTilt), a turn about down leaves the tilt error's size
  // unchanged and only turns its axes by the angle, and the next update re-expresses P at
  // the new q anyway; this saves the carry's matrix products on every sample.
  void turnHeading(double angle_rad);

  Quat attitude() const { return fromWxyz(q_); }
  const Vec4& state() const { return q_; }
  const Mat4& covariance() const { return P_; }
  void setCovariance(const Mat4& P) { P_ = P; }

 private:
  void normalise();
  void keepHeadingOutOfTilt(const Vec4& q_prior);

  Vec4 q_;
  Mat4 P_;
};

}  // namespace headingd::core
