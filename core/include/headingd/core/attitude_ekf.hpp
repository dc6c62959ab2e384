#pragma once
// The quaternion EKF of Henriksson (2013) ch. 3, Algorithm 2: the state is q_nb as a
// 4-vector (w, x, y, z); the gyroscope predicts, the accelerometer's view of gravity updates.
#include <cstdint>

#include "headingd/core/measurement_model.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// Which of the attitude's axes a generic update (AttitudeEkf::update) may correct. The others'
// uncertainty goes into the innovation's covariance but they are not moved (a "consider"
// update): the heading is the magnetometer observer's (Henriksson eq. 4.2), so an update that
// sees it too corrects the tilt only unless told otherwise.
struct AttitudeAxes {
  bool tilt = true;
  bool heading = false;
};

struct AttitudeUpdateResult {
  bool applied = false;                // false: rejected by the innovation gate, or the EKF is still starting
  double innovation_nis = 0.0;         // rᵀ S⁻¹ r: χ² with the measurement's dimension when all is well
  Vec3 turn_rad = Vec3::Zero();        // the correction about NED north, east, down
  double heading_variance_rad2 = 0.0;  // the heading's variance after it (rad²)
};

// What an update built on AttitudeEkf::update counts of its outcomes (STATUS counters).
struct FieldUpdateCounters {
  std::uint64_t applied = 0;
  std::uint64_t rejected_by_gate = 0;          // the innovation gate
  std::uint64_t rejected_by_verification = 0;  // MAU's magnetic-frame check
};

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
  // Returns the turn the update gave the attitude about NED north and east (rad; zero
  // before the first update has put P in its tilt form, start-up only).
  Eigen::Vector2d updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2);
  // The same with the measurement less certain along one direction (unit, sensor axes):
  // R = σ² I + extra_variance · u uᵀ in eq. 3.6 instead of σ² I. Done by whitening: the residual and H
  // are multiplied by I - β u uᵀ, β = 1 - 1/√(1 + extra/σ²), which makes R σ² I again. (A
  // clipped accelerometer's low-pass is short along its clipped axes: estimator.cpp.)
  Eigen::Vector2d updateGravity(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2,
                                const Vec3& uncertain_direction, double extra_variance);

  // Any measurement model's update (measurement_model.hpp: a residual, its Jacobian in the
  // error state, its noise): the EKF does not know which models exist. Eqs. 2.9 in the error
  // state of the attitude, δθ about NED with q = exp(δθ) ⊗ q̂, whose covariance is the tilt
  // block and heading_sigma_rad² about down (the heading's sigma is kept outside the EKF:
  // heading_uncertainty.hpp). Only the attitude columns of the Jacobian are used (the biases are
  // the bias filter's). Rejected, and nothing changed, when the normalised innovation squared
  // exceeds max_nis. The heading's variance after the update is returned, not kept.
  template <int N>
  AttitudeUpdateResult update(const Linearised<N>& measurement, double heading_sigma_rad, AttitudeAxes axes,
                              double max_nis);

  // Replaces the attitude (back-tracking of §3.1, heading corrections of ch. 4). The
  // covariance is kept: the replacement is a better estimate of the same state.
  void setAttitude(const Quat& q_nb);

  // Turns the attitude about NED down by angle_rad: the magnetometer observer's correction
  // (Henriksson eq. 4.2), a few 1e-4 rad per sample. The variances about the NED axes stay as
  // they are (in the tilt form that is all there is to carry; while P is still general, below
  // 0.01 rad it is not carried: the next update re-expresses P at the new q anyway).
  void turnHeading(double angle_rad);

  Quat attitude() const { return fromWxyz(q_); }
  const Vec4& state() const { return q_; }
  // P of eqs. 3.3 and 3.7b in the 4-D space of q (built from the tilt form once there is one).
  Mat4 covariance() const;
  // The covariance of the attitude's error about NED north and east (rad²): the tilt's.
  Eigen::Matrix2d tiltCovariance() const;
  void setCovariance(const Mat4& P) {
    P_ = P;
    general_ = true;
  }
  bool allFinite() const;

 private:
  void normalise();
  // whitening: I - β u uᵀ of the update above, or nullptr.
  void updateGravityGeneral(const Vec3& accel_m_s2, double accel_noise_m_s2, double f_down, const Mat3* whitening);
  Eigen::Vector2d updateGravityTilt(const Vec3& accel_m_s2, double accel_noise_m_s2, double f_down,
                                    const Mat3* whitening);
  Eigen::Vector2d updateGravityWhitened(const Vec3& accel_m_s2, double accel_noise_m_s2, double gravity_m_s2,
                                        const Mat3* whitening);
  void keepHeadingOutOfTilt(const Vec4& q_prior);

  Vec4 q_;
  // Until the first gravity update after setCovariance, P is whatever was set (it may have a
  // part along q, as the start-up P = c·I has) and the filter works on the whole 4×4 P_.
  // After it, keepHeadingOutOfTilt has made P = G(q) diag(tilt, heading) G(q)ᵀ with G the
  // earth-axis directions of q, and every step keeps that form (see the .cpp): only the
  // 2×2 tilt block and the heading variance are kept, and the 4×4 algebra becomes 2×2.
  bool general_ = true;
  Mat4 P_;
  Eigen::Matrix2d tilt_ = Eigen::Matrix2d::Zero();  // about NED north and east
  double heading_variance_ = 0.0;                   // about NED down
};

template <int N>
AttitudeUpdateResult AttitudeEkf::update(const Linearised<N>& measurement, double heading_sigma_rad, AttitudeAxes axes,
                                         double max_nis) {
  using MatN = Eigen::Matrix<double, N, N>;
  AttitudeUpdateResult result;
  if (general_) return result;  // P not yet about the NED axes: only gravity updates until then
  const Eigen::Matrix<double, N, 3> H = measurement.jacobian.template leftCols<3>();
  Mat3 P = Mat3::Zero();
  P.topLeftCorner<2, 2>() = 4.0 * tilt_;  // q + G t is a turn by 2 t (updateGravityTilt)
  P(2, 2) = heading_sigma_rad * heading_sigma_rad;
  const Eigen::Matrix<double, N, 3> HP = H * P;
  const MatN S = HP * H.transpose() + measurement.noise_covariance;
  const MatN S_inverse = S.inverse();
  result.innovation_nis = measurement.residual.dot(S_inverse * measurement.residual);
  if (!(result.innovation_nis <= max_nis)) return result;
  // P is block-diagonal (tilt, heading), so the gain of the corrected block is P's rows of that
  // block times Hᵀ S⁻¹; the considered block gets none.
  Eigen::Matrix<double, 3, N> K = HP.transpose() * S_inverse;
  if (!axes.tilt) K.template topRows<2>().setZero();
  if (!axes.heading) K.row(2).setZero();
  result.turn_rad = K * measurement.residual;
  const Mat3 P_after = P - K * HP;
  q_ = toWxyz(gyroIncrement(result.turn_rad, 1.0) * fromWxyz(q_));
  normalise();
  if (axes.tilt) {
    const double xy = 0.5 * (P_after(0, 1) + P_after(1, 0));
    tilt_ << 0.25 * P_after(0, 0), 0.25 * xy, 0.25 * xy, 0.25 * P_after(1, 1);
  }
  result.heading_variance_rad2 = P_after(2, 2);
  result.applied = true;
  return result;
}

}  // namespace headingd::core
