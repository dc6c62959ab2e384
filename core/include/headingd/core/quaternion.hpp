#pragma once
// Quaternion algebra for the attitude EKF.
//
// Convention, the same throughout headingd: Hamilton quaternions, q_nb maps body (sensor)
// vectors into NED: v_n = q_nb ⊗ v_b ⊗ q_nb*. The EKF keeps the quaternion as a 4-vector
// (w, x, y, z), the ordering Henriksson (2013) uses for q_k = (q_0, q_1, q_2, q_3).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace headingd::core {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;  // quaternion as (w, x, y, z)
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Mat34 = Eigen::Matrix<double, 3, 4>;
using Mat43 = Eigen::Matrix<double, 4, 3>;
using Quat = Eigen::Quaterniond;

Vec4 toWxyz(const Quat& q);
Quat fromWxyz(const Vec4& q);

// Henriksson (2013) eq. 2.38: dq/dt = ½ Ω(ω) q for body rates ω (q̇ = ½ q ⊗ (0, ω)).
Mat4 omegaMatrix(const Vec3& gyro_rad_s);

// Transition matrix for a constant body rate over dt: exp(½ Ω(ω) dt). Its first-order
// expansion I + ½ Ω dt is Henriksson eq. 3.2; the closed form keeps the norm exactly and
// stays accurate at the fast rotations of hand-held motion (a few rad/s).
Mat4 gyroTransition(const Vec3& gyro_rad_s, double dt_s);
// The same matrix from the increment quaternion r = gyroIncrement(ω, dt): F q = q ⊗ r.
Mat4 rightMultiplicationMatrix(const Quat& r);

// The rotation the body makes in dt at a constant rate: exp(½ ω dt) as a quaternion, so that
// q(t + dt) = q(t) ⊗ gyroIncrement (Henriksson eq. 2.34).
Quat gyroIncrement(const Vec3& gyro_rad_s, double dt_s);

// Ξ(q) with q ⊗ (0, v) = Ξ(q) v: maps gyro noise into quaternion space for Q_k (eq. 3.3).
Mat43 rightProductMatrix(const Vec4& q);

// Henriksson eq. 2.27-2.30: the earth-frame vector v_n seen in body axes, M(q) v_n with
// M = R(q)ᵀ. For a unit q this is q* ⊗ v_n ⊗ q in Hamilton terms.
Vec3 rotateEarthToBody(const Vec4& q, const Vec3& v_n);

// Henriksson eq. 2.32 / 3.5: ∂(M(q) v_n)/∂q, 3×4. The thesis prints it without the factor
// 2 of the quadratic form and with a typo in element (2,1); this is the exact derivative,
// checked against numerical differentiation in the tests.
Mat34 rotateEarthToBodyJacobian(const Vec4& q, const Vec3& v_n);

// zyx Euler angles of q_nb (Henriksson eq. 2.31, with the sign of 2.20b kept for pitch).
struct EulerAngles {
  double roll_rad;
  double pitch_rad;
  double yaw_rad;
};
EulerAngles eulerZyx(const Quat& q_nb);
// The same with the yaw known already (yawZyx(q_nb), which the estimator publishes as
// EstimatorOutput::yaw_rad): roll and pitch only, one atan2 fewer per row of a replay.
EulerAngles eulerZyx(const Quat& q_nb, double yaw_rad);
// The yaw of eulerZyx alone (one atan2 instead of two and an asin).
double yawZyx(const Quat& q_nb);

// A world-fixed vector v (sensor axes) as a sensor turned further by the small rotation
// vector -φ sees it: v + φ × v + ½ φ × (φ × v), the rotation to second order (the third-order
// term is below |φ|³/6: 3e-5 of |v| for 600 deg/s over half a 100 Hz sample).
Vec3 turnedBySmallAngle(const Vec3& v, const Vec3& phi);

// [u]×, the cross-product matrix: crossMatrix(u) v = u × v.
inline Mat3 crossMatrix(const Vec3& u) {
  Mat3 m;
  m << 0.0, -u.z(), u.y(),  //
      u.z(), 0.0, -u.x(),   //
      -u.y(), u.x(), 0.0;
  return m;
}

// Rotation by angle_rad about NED down (a heading change seen from above, clockwise positive).
Quat headingRotation(double angle_rad);

// q_nb turned by the smallest rotation that makes NED down, seen in body axes, point along
// down_b (any length): the tilt set from a measured gravity direction, the heading kept to
// first order (the rotation's axis is horizontal).
Quat tiltedTo(const Quat& q_nb, const Vec3& down_b);

// Wraps an angle to (-π, π].
double wrapAngle(double angle_rad);

// The only place the ENU convention enters: q_enu = q_EN ⊗ q_nb with q_EN the 180° turn
// about the axis halfway between north and east (BROAD README, "How an estimate is scored").
Quat nedToEnu(const Quat& q_nb);

}  // namespace headingd::core
