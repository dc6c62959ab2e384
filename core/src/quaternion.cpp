#include "headingd/core/quaternion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace headingd::core {

Vec4 toWxyz(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }

Quat fromWxyz(const Vec4& q) { return Quat(q(0), q(1), q(2), q(3)); }

Mat4 omegaMatrix(const Vec3& w) {
  Mat4 m;
  m << 0.0, -w.x(), -w.y(), -w.z(),  //
      w.x(), 0.0, w.z(), -w.y(),     //
      w.y(), -w.z(), 0.0, w.x(),     //
      w.z(), w.y(), -w.x(), 0.0;
  return m;
}

Mat4 gyroTransition(const Vec3& gyro_rad_s, double dt_s) {
  // Ω(ω)² = -|ω|² I, so exp(½ Ω dt) = cos(½|ω|dt) I + sin(½|ω|dt)/|ω| Ω: right
  // multiplication by the increment quaternion.
  return rightMultiplicationMatrix(gyroIncrement(gyro_rad_s, dt_s));
}

Mat4 rightMultiplicationMatrix(const Quat& r) {
  const double w = r.w(), x = r.x(), y = r.y(), z = r.z();
  Mat4 m;
  m << w, -x, -y, -z,  //
      x, w, z, -y,     //
      y, -z, w, x,     //
      z, y, -x, w;
  return m;
}

Quat gyroIncrement(const Vec3& gyro_rad_s, double dt_s) {
  // The series below need only the square of the half angle: no square root for them.
  const double half_angle2 = 0.25 * gyro_rad_s.squaredNorm() * dt_s * dt_s;
  // sin(x)/|ω| written as (dt/2)·sinc(x) so that a zero rate needs no special case.
  double sinc = 0.0, cos_half = 0.0;
  if (half_angle2 < 0.01) {
    // One sample turns the body by far less than 0.2 rad; there the Taylor series of sinc (to
    // x⁸) and cos (to x¹⁰) are exact to rounding (the terms left out are below 3e-18 and 3e-21)
    // and cost a fraction of std::sin and std::cos.
    const double x2 = half_angle2;
    sinc = 1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0))));
    cos_half =
        1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0 + x2 * (-1.0 / 3628800.0)))));
  } else {
    const double half_angle = std::sqrt(half_angle2);
    sinc = std::sin(half_angle) / half_angle;
    cos_half = std::cos(half_angle);
  }
  const Vec3 v = (0.5 * dt_s * sinc) * gyro_rad_s;
  return Quat(cos_half, v.x(), v.y(), v.z());
}

Mat43 rightProductMatrix(const Vec4& q) {
  Mat43 m;
  m << -q(1), -q(2), -q(3),  //
      q(0), -q(3), q(2),     //
      q(3), q(0), -q(1),     //
      -q(2), q(1), q(0);
  return m;
}

Vec3 rotateEarthToBody(const Vec4& q, const Vec3& v) {
  const double q0 = q(0), q1 = q(1), q2 = q(2), q3 = q(3);
  Mat3 m;  // Henriksson eq. 2.30
  m << q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 + q0 * q3), 2 * (q1 * q3 - q0 * q2), 2 * (q1 * q2 - q0 * q3),
      q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 + q0 * q1), 2 * (q0 * q2 + q1 * q3), 2 * (q2 * q3 - q0 * q1),
      q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3;
  return m * v;
}

Mat34 rotateEarthToBodyJacobian(const Vec4& q, const Vec3& v) {
  const double q0 = q(0), q1 = q(1), q2 = q(2), q3 = q(3);
  const double x = v.x(), y = v.y(), z = v.z();
  Mat34 h;
  // Column j is (∂M/∂q_j) v; each row is the scalar product of eq. 2.32, times 2.
  h << q0 * x + q3 * y - q2 * z, q1 * x + q2 * y + q3 * z, -q2 * x + q1 * y - q0 * z, -q3 * x + q0 * y + q1 * z,
      -q3 * x + q0 * y + q1 * z, q2 * x - q1 * y + q0 * z, q1 * x + q2 * y + q3 * z, -q0 * x - q3 * y + q2 * z,
      q2 * x - q1 * y + q0 * z, q3 * x - q0 * y - q1 * z, q0 * x + q3 * y - q2 * z, q1 * x + q2 * y + q3 * z;
  return 2.0 * h;
}

EulerAngles eulerZyx(const Quat& q_nb) { return eulerZyx(q_nb, yawZyx(q_nb)); }

EulerAngles eulerZyx(const Quat& q_nb, double yaw_rad) {
  const double q0 = q_nb.w(), q1 = q_nb.x(), q2 = q_nb.y(), q3 = q_nb.z();
  const double sin_pitch = std::clamp(2.0 * (q0 * q2 - q1 * q3), -1.0, 1.0);
  return {std::atan2(2.0 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3), std::asin(sin_pitch), yaw_rad};
}

double yawZyx(const Quat& q_nb) {
  const double q0 = q_nb.w(), q1 = q_nb.x(), q2 = q_nb.y(), q3 = q_nb.z();
  return std::atan2(2.0 * (q1 * q2 + q0 * q3), q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3);
}

Quat headingRotation(double angle_rad) { return Quat(Eigen::AngleAxisd(angle_rad, Vec3::UnitZ())); }

double wrapAngle(double a) {
  constexpr double kPi = std::numbers::pi;
  a = std::remainder(a, 2.0 * kPi);  // [-π, π]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

Quat nedToEnu(const Quat& q_nb) {
  const double h = std::sqrt(0.5);
  return Quat(0.0, h, h, 0.0) * q_nb;
}

Vec3 turnedBySmallAngle(const Vec3& v, const Vec3& phi) {
  const Vec3 once = phi.cross(v);
  return v + once + 0.5 * phi.cross(once);
}

Quat tiltedTo(const Quat& q_nb, const Vec3& down_b) {
  // q ⊗ r with r taking down_b onto the down q_nb has in body axes: then q ⊗ r maps down_b
  // onto NED down.
  const Vec3 down_now = q_nb.conjugate() * Vec3::UnitZ();
  return (q_nb * Quat::FromTwoVectors(down_b, down_now)).normalized();
}

}  // namespace headingd::core
