#include "headingd/core/attitude_ekf.hpp"

namespace headingd::core {

AttitudeEkf::AttitudeEkf() : q_(1.0, 0.0, 0.0, 0.0), P_(1000.0 * Mat4::Identity()) {}

void AttitudeEkf::predict(const Vec3& gyro_rad_s, double dt_s, double gyro_noise_rad_s) {
  const Mat4 F = gyroTransition(gyro_rad_s, dt_s);  // eq. 3.2
  const Mat43 xi = rightProductMatrix(q_);
  const double s = 0.5 * dt_s * gyro_noise_rad_s;
  q_ = F * q_;
  P_ = F * P_ * F.transpose() + (s * s) * xi * xi.transpose();  // eq. 3.3
  normalise();
}

void AttitudeEkf::updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2) {
  const Vec3 f_n(0.0, 0.0, -gravity_m_s2);
  const Mat34 H = rotateEarthToBodyJacobian(q_, f_n);  // eq. 3.5
  const Mat3 S = H * P_ * H.transpose() + (accel_noise_m_s2 * accel_noise_m_s2) * Mat3::Identity();
  const Mat43 K = P_ * H.transpose() * S.inverse();  // eq. 3.6
  q_ += K * (accel_m_s2 - rotateEarthToBody(q_, f_n));  // eq. 3.7a (EKF form 2.9a)
  // Eq. 3.7b in Joseph form: the same covariance in exact arithmetic, but it stays
  // symmetric positive semi-definite in floating point over hours of 100+ Hz updates.
  const Mat4 I_KH = Mat4::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + (accel_noise_m_s2 * accel_noise_m_s2) * K * K.transpose();
  normalise();  // eq. 3.8
}

void AttitudeEkf::setAttitude(const Quat& q_nb) {
  q_ = toWxyz(q_nb.normalized());
  if (q_(0) < 0.0) q_ = -q_;
}

void AttitudeEkf::normalise() {
  q_ /= q_.norm();
  // The norm of q is not a degree of freedom: remove it from P so that the update spends its
  // gain on rotation, not on a length that eq. 3.8 discards.
  const Mat4 project = Mat4::Identity() - q_ * q_.transpose();
  P_ = project * P_ * project.transpose();
  // q and -q are the same rotation; keeping w ≥ 0 keeps the state continuous for output.
  if (q_(0) < 0.0) q_ = -q_;
}

}  // namespace headingd::core
