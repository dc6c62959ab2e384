#include "headingd/core/measurement_model.hpp"

#include <cmath>

namespace headingd::core {

NavigationState perturbed(const NavigationState& x, const ErrorVector& dx) {
  NavigationState moved = x;
  const Vec3 turn = dx.segment<3>(error_state::kAttitude);
  moved.q_nb = (Quat(rotationMatrix(turn)) * x.q_nb).normalized();
  moved.gyro_bias_rad_s += dx.segment<3>(error_state::kGyroBias);
  moved.accel_bias_m_s2 += dx.segment<3>(error_state::kAccelBias);
  return moved;
}

Mat3 rotationMatrix(const Vec3& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0.0) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
}

Mat3 so3LeftJacobian(const Vec3& rotation_vector) {
  // J_l = I + (1 - cos a)/a² [φ]× + (a - sin a)/a³ [φ]×²; below 1e-4 rad the series' first
  // terms, 1/2 - a²/24 and 1/6 - a²/120 (the rest below 1e-18).
  const double a2 = rotation_vector.squaredNorm();
  const double a = std::sqrt(a2);
  const double first = a < 1e-4 ? 0.5 - a2 / 24.0 : (1.0 - std::cos(a)) / a2;
  const double second = a < 1e-4 ? 1.0 / 6.0 - a2 / 120.0 : (a - std::sin(a)) / (a2 * a);
  const Mat3 cross = crossMatrix(rotation_vector);
  return Mat3::Identity() + first * cross + second * cross * cross;
}

}  // namespace headingd::core
