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

// rotateEarthToBody and its Jacobian (eqs. 2.30, 3.5) for f_n = (0, 0, -g), with the terms
// that multiply the zero north and east components left out (the results are the same).
Vec3 gravityInBody(const Vec4& q, double down_m_s2) {
  const double q0 = q(0), q1 = q(1), q2 = q(2), q3 = q(3);
  return {2 * (q1 * q3 - q0 * q2) * down_m_s2, 2 * (q2 * q3 + q0 * q1) * down_m_s2,
          (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * down_m_s2};
}

Mat34 gravityInBodyJacobian(const Vec4& q, double down_m_s2) {
  const double q0 = q(0), q1 = q(1), q2 = q(2), q3 = q(3), z = down_m_s2;
  Mat34 h;
  h << -q2 * z, q3 * z, -q0 * z, q1 * z,  //
      q1 * z, q0 * z, q3 * z, q2 * z,     //
      q0 * z, -q1 * z, -q2 * z, q3 * z;
  return 2.0 * h;
}

// Inverse of a symmetric positive definite 3×3 matrix (S of eq. 3.6) by its adjugate: the
// same cofactor formula as Eigen's general inverse, with the six distinct cofactors only.
Mat3 symmetricInverse(const Mat3& S) {
  const double a = S(0, 0), b = S(0, 1), c = S(0, 2), d = S(1, 1), e = S(1, 2), f = S(2, 2);
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double c11 = a * f - c * c, c12 = b * c - a * e, c22 = a * d - b * b;
  const double inverse_det = 1.0 / (a * c00 + b * c01 + c * c02);
  Mat3 inverse;
  inverse << c00, c01, c02,  //
      c01, c11, c12,         //
      c02, c12, c22;
  return inverse_det * inverse;
}

}  // namespace

AttitudeEkf::AttitudeEkf() : q_(1.0, 0.0, 0.0, 0.0), P_(1000.0 * Mat4::Identity()) {}

void AttitudeEkf::predict(const Quat& increment, double dt_s, double gyro_noise_rad_s) {
  const Mat4 F = rightMultiplicationMatrix(increment);  // eq. 3.2 in closed form
  const double s = 0.5 * dt_s * gyro_noise_rad_s;
  const double s2 = s * s;
  // Q = s² Ξ Ξᵀ = s² (|q|² I - q qᵀ): q and the three columns of Ξ(q) are orthogonal, each of
  // length |q| (together they form the left-multiplication matrix of q). P stays symmetric, so
  // only its upper triangle is computed and mirrored.
  if (general_) {
    const double q_norm2 = q_.squaredNorm();
    const Mat4 FP = F * P_;
    Mat4 P;
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i <= j; ++i) {
        const double q_term = (i == j ? q_norm2 : 0.0) - q_(i) * q_(j);
        P(i, j) = P(j, i) = FP.row(i).dot(F.row(j)) + s2 * q_term;  // eq. 3.3
      }
    }
    P_ = P;
    // F is orthogonal and Q lies in the tangent space of q, so P stays orthogonal to q (up to
    // rounding, which the next update's re-expression of P removes).
  } else {
    // F G(q) = G(F q): the earth-axis directions move with q (e_i ⊗ q ⊗ r), so F P Fᵀ keeps
    // the same tilt and heading variances, and Q = s² G Gᵀ adds s² to each (taken at the
    // new q rather than the old: they differ by |ω| dt/2 of Q, far below its own accuracy).
    tilt_.diagonal().array() += s2;
    heading_variance_ += s2;
  }
  q_ = F * q_;
  normalise();
}

Eigen::Vector2d AttitudeEkf::updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2) {
  return updateGravityWhitened(accel_m_s2, accel_noise_m_s2, gravity_m_s2, nullptr);
}

Eigen::Vector2d AttitudeEkf::updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2,
                                           const Vec3& uncertain_direction, double extra_variance) {
  if (!(extra_variance > 0.0)) return updateGravity(accel_m_s2, accel_noise_m_s2, gravity_m_s2);
  const double beta = 1.0 - 1.0 / std::sqrt(1.0 + extra_variance / (accel_noise_m_s2 * accel_noise_m_s2));
  const Mat3 whitening = Mat3::Identity() - beta * uncertain_direction * uncertain_direction.transpose();
  return updateGravityWhitened(accel_m_s2, accel_noise_m_s2, gravity_m_s2, &whitening);
}

Eigen::Vector2d AttitudeEkf::updateGravityWhitened(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2,
                                                   const Mat3* whitening) {
  const double f_down = -gravity_m_s2;  // f_n = (0, 0, -g)
  if (general_) {
    updateGravityGeneral(accel_m_s2, accel_noise_m_s2, f_down, whitening);
    return Eigen::Vector2d::Zero();
  }
  return updateGravityTilt(accel_m_s2, accel_noise_m_s2, f_down, whitening);
}

Eigen::Vector2d AttitudeEkf::updateGravityTilt(const Vec3& accel_m_s2, double accel_noise_m_s2, double f_down,
                                               const Mat3* whitening) {
  // Eqs. 3.5-3.7 with P = G diag(A, heading) Gᵀ (A: 2×2 tilt block, G = earth-axis
  // directions of q). H G = (J, 0): gravity does not change when the body turns about down.
  // Then H P Hᵀ = J A Jᵀ, K = G₂ A Jᵀ S⁻¹, and by the push-through identity
  // Jᵀ (σ² I + J A Jᵀ)⁻¹ = (σ² I + Jᵀ J A)⁻¹ Jᵀ the 3×3 inverse of S becomes a 2×2 one:
  //   B = A (σ² I + Jᵀ J A)⁻¹,  K = G₂ B Jᵀ,  A ← A - B Jᵀ J A.
  // The heading variance is left as it is, as the 4×4 update leaves it.
  const Mat34 H = gravityInBodyJacobian(q_, f_down);  // eq. 3.5
  const Mat43 G = earthAxisDirections(q_);
  Eigen::Matrix<double, 3, 2> J = H * G.leftCols<2>();
  Vec3 residual = accel_m_s2 - gravityInBody(q_, f_down);
  if (whitening != nullptr) {
    J = *whitening * J;
    residual = *whitening * residual;
  }
  const Eigen::Matrix2d W = J.transpose() * J;
  Eigen::Matrix2d N = W * tilt_;
  N.diagonal().array() += accel_noise_m_s2 * accel_noise_m_s2;
  const double inverse_det = 1.0 / (N(0, 0) * N(1, 1) - N(0, 1) * N(1, 0));
  Eigen::Matrix2d N_inverse;
  N_inverse << N(1, 1), -N(0, 1), -N(1, 0), N(0, 0);
  const Eigen::Matrix2d B = tilt_ * (inverse_det * N_inverse);
  const Eigen::Vector2d turn = B * (J.transpose() * residual);  // eq. 3.7a
  q_ += G.leftCols<2>() * turn;
  const Eigen::Matrix2d A = tilt_ - B * (W * tilt_);  // eq. 3.7b
  const double xy = 0.5 * (A(0, 1) + A(1, 0));        // symmetric, as keepHeadingOutOfTilt keeps it
  tilt_ << A(0, 0), xy, xy, A(1, 1);
  normalise();  // eq. 3.8
  // P about the NED axes is re-expressed at the new q by keeping A and the heading variance.
  // q + G₂ t = (1 + t_x e_x + t_y e_y) ⊗ q: a turn by 2 t about the NED axes.
  return 2.0 * turn;
}

void AttitudeEkf::updateGravityGeneral(const Vec3& accel_m_s2, double accel_noise_m_s2, double f_down,
                                       const Mat3* whitening) {
  Mat34 H = gravityInBodyJacobian(q_, f_down);  // eq. 3.5
  Vec3 residual = accel_m_s2 - gravityInBody(q_, f_down);
  if (whitening != nullptr) {
    H = *whitening * H;
    residual = *whitening * residual;
  }
  // P is symmetric, so P Hᵀ = (H P)ᵀ: one product serves S, K and the update of P.
  const Mat34 HP = H * P_;
  Mat3 S = HP * H.transpose();
  S.diagonal().array() += accel_noise_m_s2 * accel_noise_m_s2;
  const Mat43 K = HP.transpose() * symmetricInverse(S);  // eq. 3.6
  const Vec4 q_prior = q_;                               // P below belongs to this linearisation point
  q_ += K * residual;                                    // eq. 3.7a (EKF form 2.9a)
  P_ -= K * HP;                                          // eq. 3.7b; kept symmetric by keepHeadingOutOfTilt below
  normalise();                                           // eq. 3.8
  keepHeadingOutOfTilt(q_prior);
}

void AttitudeEkf::keepHeadingOutOfTilt(const Vec4& q_prior) {
  // Gravity says nothing about heading, and heading is the observer's (eq. 4.2), so the
  // covariance between heading and tilt must stay zero: otherwise the accelerometer, through
  // K = P Hᵀ S⁻¹, turns the heading. In the 4-D state the heading direction e_z ⊗ q moves
  // with every update of q, so P is re-expressed about the NED axes at the updated q (the
  // same carry as in setAttitude) and the heading-tilt terms are dropped.
  const Eigen::Matrix<double, 4, 3> before = earthAxisDirections(q_prior);
  // Only the entries of P about the NED axes that survive are computed: the tilt block
  // (symmetrised) and the heading variance.
  const Eigen::Matrix<double, 4, 3> P_before = P_ * before;
  const double tilt_xx = before.col(0).dot(P_before.col(0));
  const double tilt_xy = 0.5 * (before.col(0).dot(P_before.col(1)) + before.col(1).dot(P_before.col(0)));
  const double tilt_yy = before.col(1).dot(P_before.col(1));
  const double heading = before.col(2).dot(P_before.col(2));
  // P = G(q) · [[xx, xy, 0], [xy, yy, 0], [0, 0, heading]] · G(q)ᵀ: from now on only the
  // middle matrix is kept (the tilt form of the header).
  tilt_ << tilt_xx, tilt_xy, tilt_xy, tilt_yy;
  heading_variance_ = heading;
  general_ = false;
}

Mat4 AttitudeEkf::covariance() const {
  if (general_) return P_;
  const Mat43 G = earthAxisDirections(q_);
  Mat3 T = Mat3::Zero();
  T.topLeftCorner<2, 2>() = tilt_;
  T(2, 2) = heading_variance_;
  return G * T * G.transpose();
}

Eigen::Matrix2d AttitudeEkf::tiltCovariance() const {
  // q + G t is a turn by 2 t about the NED axes (updateGravityTilt), so angles are 2 t.
  if (!general_) return 4.0 * tilt_;
  const Eigen::Matrix<double, 4, 2> G = earthAxisDirections(q_).leftCols<2>();
  return 4.0 * G.transpose() * P_ * G;
}

bool AttitudeEkf::allFinite() const {
  return q_.allFinite() && (general_ ? P_.allFinite() : tilt_.allFinite() && std::isfinite(heading_variance_));
}

void AttitudeEkf::setAttitude(const Quat& q_nb) {
  Vec4 q_new = toWxyz(q_nb.normalized());
  if (q_new(0) < 0.0) q_new = -q_new;
  // P lives in the 4-D space of q, where "tilt" and "heading" are directions that depend on
  // q itself. Moving q without moving P would mix the two: the well-known tilt would look
  // like heading and the accelerometer would start to turn the heading. Carry P over so that
  // its covariance about the NED axes stays the same.
  // (In the tilt form that carry is built in: the variances are about the NED axes.)
  if (general_) {
    const Mat4 carry = earthAxisDirections(q_new) * earthAxisDirections(q_).transpose();
    P_ = carry * P_ * carry.transpose();
  }
  q_ = q_new;
}

void AttitudeEkf::turnHeading(double angle_rad) {
  // headingRotation(angle) ⊗ q written out: the turn (cos ½a, 0, 0, sin ½a) has only w and z.
  // It is the exponential of the rotation vector (0, 0, a), which gyroIncrement computes
  // without std::sin and std::cos for the small angles of the observer.
  const Quat turn = gyroIncrement(Vec3(0.0, 0.0, angle_rad), 1.0);
  const double c = turn.w(), s = turn.z();
  const Vec4 turned(c * q_(0) - s * q_(3), c * q_(1) - s * q_(2), c * q_(2) + s * q_(1), c * q_(3) + s * q_(0));
  if (std::abs(angle_rad) >= 0.01) {
    setAttitude(fromWxyz(turned));
    return;
  }
  q_ = turned;
  normalise();
}

void AttitudeEkf::normalise() {
  // After a rotation (predict, a small turnHeading) |q|² is 1 to a few ulps, and there
  // 1/|q| = 1.5 - 0.5|q|² to rounding (the next term, 3/8 (|q|² - 1)², is below 4e-17): the
  // square root and the division are needed only after a measurement update.
  const double norm2 = q_.squaredNorm();
  q_ *= std::abs(norm2 - 1.0) < 1e-8 ? 1.5 - 0.5 * norm2 : 1.0 / std::sqrt(norm2);
  // q and -q are the same rotation; keeping w ≥ 0 keeps the state continuous for output.
  if (q_(0) < 0.0) q_ = -q_;
}

}  // namespace headingd::core
