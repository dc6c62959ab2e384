#include "headingd/core/attitude_ekf.hpp"

#include <cmath>

namespace headingd::core {

namespace {

// Columns e_x ⊗ q, e_y ⊗ q, e_z ⊗ q: the directions in which q moves when the attitude turns
// about the NED axes. For a unit q they are orthonormal and orthogonal to q.
Eigen::Matrix<double, 4, 3> earthAxisDirections(const Vec4& q) {
  Eigen::Matrix<double, 4, 3> g;
  g << -q(1), -q(2), -q(3),  //
      q(0), q(3), -q(2),     //
      -q(3), q(0), q(1),     //
      q(2), -q(1), q(0);
  return g;
}

}  // namespace

AttitudeEkf::AttitudeEkf() : q_(1.0, 0.0, 0.0, 0.0), P_(1000.0 * Mat4::Identity()) {}

void AttitudeEkf::predict(const Quat& increment, double dt_s, double gyro_noise_rad_s) {
  const Mat4 F = rightMultiplicationMatrix(increment);  // eq. 3.2 in closed form
  const Mat43 xi = rightProductMatrix(q_);
  const double s = 0.5 * dt_s * gyro_noise_rad_s;
  q_ = F * q_;
  P_ = F * P_ * F.transpose() + (s * s) * xi * xi.transpose();  // eq. 3.3
  normalise();
  // F is orthogonal and Q lies in the tangent space of q, so P stays orthogonal to q (up to
  // rounding, which the next update's re-expression of P removes).
}

void AttitudeEkf::updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2) {
  const Vec3 f_n(0.0, 0.0, -gravity_m_s2);
  const Mat34 H = rotateEarthToBodyJacobian(q_, f_n);  // eq. 3.5
  const Mat3 S = H * P_ * H.transpose() + (accel_noise_m_s2 * accel_noise_m_s2) * Mat3::Identity();
  const Mat43 K = P_ * H.transpose() * S.inverse();  // eq. 3.6
  const Vec4 q_prior = q_;  // P below belongs to this linearisation point
  q_ += K * (accel_m_s2 - rotateEarthToBody(q_, f_n));  // eq. 3.7a (EKF form 2.9a)
  P_ -= K * (H * P_);  // eq. 3.7b; kept symmetric by keepHeadingOutOfTilt below
  normalise();  // eq. 3.8
  keepHeadingOutOfTilt(q_prior);
}

void AttitudeEkf::keepHeadingOutOfTilt(const Vec4& q_prior) {
  // Gravity says nothing about heading, and heading is the observer's (eq. 4.2), so the
  // covariance between heading and tilt must stay zero: otherwise the accelerometer, through
  // K = P Hᵀ S⁻¹, turns the heading. In the 4-D state the heading direction e_z ⊗ q moves
  // with every update of q, so P is re-expressed about the NED axes at the updated q (the
  // same carry as in setAttitude) and the heading-tilt terms are dropped.
  const Eigen::Matrix<double, 4, 3> before = earthAxisDirections(q_prior);
  const Eigen::Matrix<double, 4, 3> after = earthAxisDirections(q_);
  Mat3 about_ned_axes = before.transpose() * P_ * before;
  about_ned_axes = 0.5 * (about_ned_axes + about_ned_axes.transpose()).eval();
  about_ned_axes.block<2, 1>(0, 2).setZero();
  about_ned_axes.block<1, 2>(2, 0).setZero();
  P_ = after * about_ned_axes * after.transpose();
}

void AttitudeEkf::setAttitude(const Quat& q_nb) {
  Vec4 q_new = toWxyz(q_nb.normalized());
  if (q_new(0) < 0.0) q_new = -q_new;
  // P lives in the 4-D space of q, where "tilt" and "heading" are directions that depend on
  // q itself. Moving q without moving P would mix the two: the well-known tilt would look
  // like heading and the accelerometer would start to turn the heading. Carry P over so that
  // its covariance about the NED axes stays the same.
  const Mat4 carry = earthAxisDirections(q_new) * earthAxisDirections(q_).transpose();
  P_ = carry * P_ * carry.transpose();
  q_ = q_new;
}

void AttitudeEkf::turnHeading(double angle_rad) {
  const Quat turned = headingRotation(angle_rad) * fromWxyz(q_);
  if (std::abs(angle_rad) >= 0.01) {
    setAttitude(turned);
    return;
  }
  q_ = toWxyz(turned);
  normalise();
}

void AttitudeEkf::normalise() {
  q_ /= q_.norm();
  // q and -q are the same rotation; keeping w ≥ 0 keeps the state continuous for output.
  if (q_(0) < 0.0) q_ = -q_;
}

}  // namespace headingd::core
