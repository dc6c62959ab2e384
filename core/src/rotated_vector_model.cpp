#include "headingd/core/rotated_vector_model.hpp"

namespace headingd::core {

Linearised<3> RotatedVectorModel::linearise(const NavigationState& x, const Vec3& before, const Vec3& after,
                                            const Vec3& gyro_rad_s, double interval_s) const {
  const Vec3 turn = -(gyro_rad_s - x.gyro_bias_rad_s) * interval_s;
  const Mat3 rotation = rotationMatrix(turn);
  const Vec3 bias = with_accel_bias ? x.accel_bias_m_s2 : Vec3::Zero();
  const Vec3 turned = rotation * (before - bias);
  Linearised<3> l;
  l.residual = after - (turned + bias);
  l.jacobian.block<3, 3>(0, error_state::kGyroBias) = -crossMatrix(turned) * so3LeftJacobian(turn) * interval_s;
  if (with_accel_bias) l.jacobian.block<3, 3>(0, error_state::kAccelBias) = Mat3::Identity() - rotation;
  l.noise_covariance = 2.0 * noise_sigma * noise_sigma * Mat3::Identity();
  return l;
}

void GyroRotationIntegral::start(const Quat& frame_from_sensor) {
  start_inverse_ = frame_from_sensor.conjugate();
  start_from_end_.setIdentity();
  bias_turn_.setZero();
  interval_s_ = 0.0;
}

void GyroRotationIntegral::add(const Quat& frame_from_sensor, double dt_s) {
  const Mat3 now = (start_inverse_ * frame_from_sensor).toRotationMatrix();
  bias_turn_ += 0.5 * dt_s * (start_from_end_ + now);
  start_from_end_ = now;
  interval_s_ += dt_s;
}

Linearised<3> RotatedVectorModel::linearise(const NavigationState& x, const Vec3& before, const Vec3& after,
                                            const GyroRotationIntegral& interval) const {
  const Mat3& C = interval.startFromEnd();
  const Vec3 bias = with_accel_bias ? x.accel_bias_m_s2 : Vec3::Zero();
  const Vec3 u = before - bias;
  Linearised<3> l;
  l.residual = after - (C.transpose() * u + bias);
  l.jacobian.block<3, 3>(0, error_state::kGyroBias) = -C.transpose() * crossMatrix(u) * interval.biasTurn();
  if (with_accel_bias) l.jacobian.block<3, 3>(0, error_state::kAccelBias) = Mat3::Identity() - C.transpose();
  l.noise_covariance = 2.0 * noise_sigma * noise_sigma * Mat3::Identity();
  return l;
}

}  // namespace headingd::core
