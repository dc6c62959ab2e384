#pragma once
// The EKF one-step-ahead predictor of Kok & Schön (2016) §5.2, templated on the scalar so
// that Ceres's Jets differentiate the likelihood (eq. 6) exactly.
//
// Multiplicative EKF (K&S §5.2, Kok 2014 §3.3): the state is a 3-vector η, the orientation
// deviation in the navigation frame (NED) from the linearisation point q̃_nb,
//     q_nb = exp(η/2) ⊗ q̃_nb,
// which is reset to zero after each measurement update by moving q̃. With the deviation in
// the navigation frame the dynamics are η_{t+1} = η_t - T R̃_nb e_ω, so F = I and the gyro
// noise enters as G Σω Gᵀ with G = T R̃_nb.
//
// Measurement models, with R_bn = R̃_bn (I - [η×]) to first order:
//   accelerometer, eq. 16 at zero acceleration: y_a = -R_bn g_n,       H_a = -R̃_bn [g_n×]
//   magnetometer,  eq. 13:                      y_m = D R_bn m_n + o,  H_m = D R̃_bn [m_n×]
// with g_n = (0, 0, g) in NED and m_n the unit field (cos δ, 0, sin δ), δ the dip (positive
// below the horizon; K&S eq. 8b write it with z up).
//
// The two triads are processed one after the other. Their noises are independent (eq. 2), so
// p(y_a, y_m | y_1:t-1) = p(y_a | y_1:t-1) p(y_m | y_a, y_1:t-1): each factor has a 3×3 S,
// which costs less than the 6×6 of a joint update, and the magnetometer is linearised at the
// attitude the accelerometer has already corrected.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace headingd::calib {

template <typename T>
using Vec3T = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3T = Eigen::Matrix<T, 3, 3>;
template <typename T>
using QuatT = Eigen::Quaternion<T>;

// The value of a scalar without its derivatives (Jet::a), for reporting.
inline double scalarPart(double x) { return x; }
template <typename J>
requires requires(const J& j) { j.a; }
double scalarPart(const J& j) { return j.a; }

// [v×]: the matrix with [v×] w = v × w.
template <typename T>
Mat3T<T> crossMatrix(const Vec3T<T>& v) {
  Mat3T<T> m;
  m << T(0.0), -v.z(), v.y(),  //
      v.z(), T(0.0), -v.x(),   //
      -v.y(), v.x(), T(0.0);
  return m;
}

// exp(r/2) as a unit quaternion: the rotation by |r| about r. Below 1e-6 rad the series
// avoids dividing by |r| (and the infinite derivative of √ at 0 for Jets).
template <typename T>
QuatT<T> quaternionFromRotationVector(const Vec3T<T>& r) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Vec3T<T> half = T(0.5) * r;
  const T n2 = half.squaredNorm();
  T w, s;
  if (n2 < T(1e-12)) {
    w = T(1.0) - n2 / T(2.0);
    s = T(1.0) - n2 / T(6.0);
  } else {
    const T n = sqrt(n2);
    w = cos(n);
    s = sin(n) / n;
  }
  return QuatT<T>(w, s * half.x(), s * half.y(), s * half.z());
}

// Lower Cholesky factor of a symmetric 3×3 S; false if S is not positive definite.
template <typename T>
bool cholesky3(const Mat3T<T>& S, Mat3T<T>& L) {
  using std::sqrt;
  L.setZero();
  if (!(S(0, 0) > T(0.0))) return false;
  L(0, 0) = sqrt(S(0, 0));
  L(1, 0) = S(1, 0) / L(0, 0);
  L(2, 0) = S(2, 0) / L(0, 0);
  const T d1 = S(1, 1) - L(1, 0) * L(1, 0);
  if (!(d1 > T(0.0))) return false;
  L(1, 1) = sqrt(d1);
  L(2, 1) = (S(2, 1) - L(2, 0) * L(1, 0)) / L(1, 1);
  const T d2 = S(2, 2) - L(2, 0) * L(2, 0) - L(2, 1) * L(2, 1);
  if (!(d2 > T(0.0))) return false;
  L(2, 2) = sqrt(d2);
  return true;
}

// L⁻¹ for a lower-triangular L with a non-zero diagonal.
template <typename T>
Mat3T<T> lowerInverse(const Mat3T<T>& L) {
  Mat3T<T> inv = Mat3T<T>::Zero();
  inv(0, 0) = T(1.0) / L(0, 0);
  inv(1, 1) = T(1.0) / L(1, 1);
  inv(2, 2) = T(1.0) / L(2, 2);
  inv(1, 0) = -L(1, 0) * inv(0, 0) * inv(1, 1);
  inv(2, 1) = -L(2, 1) * inv(1, 1) * inv(2, 2);
  inv(2, 0) = -(L(2, 0) * inv(0, 0) + L(2, 1) * inv(1, 0)) * inv(2, 2);
  return inv;
}

// What the EKF is told about the sensors: θ of K&S eq. 17 with m_n from the dip.
template <typename T>
struct MlModel {
  Mat3T<T> D = Mat3T<T>::Identity();          // eq. 13, dimensionless
  Vec3T<T> offset = Vec3T<T>::Zero();         // eq. 13, in units of the field norm
  Vec3T<T> field_n = Vec3T<T>::UnitX();       // unit local field in NED, eq. 8b
  Vec3T<T> gyro_bias = Vec3T<T>::Zero();      // eq. 15, rad/s
  Mat3T<T> gyro_cov = Mat3T<T>::Identity();   // Σω, (rad/s)²
  Mat3T<T> accel_cov = Mat3T<T>::Identity();  // Σa, (m/s²)²
  Mat3T<T> mag_cov = Mat3T<T>::Identity();    // Σm, (field norm)²
};

// Field from the dip: m_n = (cos δ, 0, sin δ) in NED (K&S eq. 8b with z down).
template <typename T>
Vec3T<T> fieldFromDip(const T& dip_rad) {
  using std::cos;
  using std::sin;
  return Vec3T<T>(cos(dip_rad), T(0.0), sin(dip_rad));
}

// One Gaussian factor of eq. 6: ½(εᵀ S⁻¹ ε + log det S), and the whitened innovation
// L⁻¹ε (S = L Lᵀ) that K&S §7.2 call the normalised residual.
template <typename T>
struct InnovationTerm {
  T cost = T(0.0);
  Vec3T<T> normalised = Vec3T<T>::Zero();
  bool ok = false;
};

template <typename T>
class MlEkf {
 public:
  MlEkf(const MlModel<T>& model, double gravity_m_s2) : model_(model), gravity_n_(T(0.0), T(0.0), T(gravity_m_s2)) {}

  // TRIAD from a mean accelerometer (m/s²) and a mean raw magnetometer (field units): down
  // is -y_a in body axes, the calibrated field D⁻¹(y_m - o) fixes north.
  void initialise(const Vec3T<T>& accel, const Vec3T<T>& mag_raw, double attitude_sigma_rad) {
    const Vec3T<T> down_b = (-accel).normalized();
    const Vec3T<T> m_b = model_.D.inverse() * (mag_raw - model_.offset);
    const Vec3T<T> east_b = down_b.cross(m_b).normalized();
    const Vec3T<T> north_b = east_b.cross(down_b);
    Mat3T<T> r_bn;
    r_bn.col(0) = north_b;
    r_bn.col(1) = east_b;
    r_bn.col(2) = down_b;
    setAttitude(QuatT<T>(Mat3T<T>(r_bn.transpose())), attitude_sigma_rad);
  }

  // From the accelerometer alone (heading 0): for the inertial-only EKF of K&S §6.2.
  void initialiseFromGravity(const Vec3T<T>& accel, double attitude_sigma_rad) {
    const Vec3T<T> down_b = (-accel).normalized();
    // The rotation taking body down onto NED down, about down_b × z.
    setAttitude(QuatT<T>::FromTwoVectors(down_b, Vec3T<T>::UnitZ()), attitude_sigma_rad);
  }

  void setAttitude(const QuatT<T>& q_nb, double attitude_sigma_rad) {
    q_nb_ = q_nb.normalized();
    P_ = Mat3T<T>::Identity() * T(attitude_sigma_rad * attitude_sigma_rad);
  }

  // The state exactly as given (no normalisation): to restart the recursion at a step
  // stored earlier (ml_adjoint_gradient.cpp).
  void setState(const QuatT<T>& q_nb, const Mat3T<T>& P) {
    q_nb_ = q_nb;
    P_ = P;
  }

  // Time update with the gyro over dt (K&S eq. 1a, 15): q̃ ← q̃ ⊗ exp(T(y_ω - δω)/2).
  // `noise_dt2_s2` is Σ dt_i² of the gyro samples behind this step: dt² for one sample, less
  // than dt² when several were pre-integrated (ml_data.hpp, decimation), whose independent
  // noises add up to Σ dt_i² Σω, not (Σ dt_i)² Σω.
  void predict(const Eigen::Vector3d& gyro_rad_s, double dt_s, double noise_dt2_s2) {
    if (dt_s <= 0.0) return;
    const Vec3T<T> rate = gyro_rad_s.cast<T>() - model_.gyro_bias;
    q_nb_ = (q_nb_ * quaternionFromRotationVector<T>(rate * T(dt_s))).normalized();
    const Mat3T<T> R = q_nb_.toRotationMatrix();
    P_ += (R * model_.gyro_cov * R.transpose()) * T(noise_dt2_s2);
  }
  void predict(const Eigen::Vector3d& gyro_rad_s, double dt_s) { predict(gyro_rad_s, dt_s, dt_s * dt_s); }

  // Predicted measurements and their Jacobians with respect to η at the current q̃.
  Vec3T<T> predictedAccel() const { return -(q_nb_.conjugate() * gravity_n_); }
  Mat3T<T> accelJacobian() const { return -q_nb_.conjugate().toRotationMatrix() * crossMatrix<T>(gravity_n_); }
  Vec3T<T> predictedMag() const { return model_.D * (q_nb_.conjugate() * model_.field_n) + model_.offset; }
  Mat3T<T> magJacobian() const {
    return model_.D * q_nb_.conjugate().toRotationMatrix() * crossMatrix<T>(model_.field_n);
  }

  InnovationTerm<T> updateAccel(const Eigen::Vector3d& accel_m_s2) {
    return update(accel_m_s2.cast<T>() - predictedAccel(), accelJacobian(), model_.accel_cov);
  }
  InnovationTerm<T> updateMag(const Eigen::Vector3d& mag_unit) {
    return update(mag_unit.cast<T>() - predictedMag(), magJacobian(), model_.mag_cov);
  }

  // The mean of `count` readings taken over the last step, where reading i saw the body
  // turned by R_i relative to now (from the gyro) and `mean_rotation` = mean R_i: since the
  // models are linear in R_bn, the mean reads y = -M R_bn g_n (accelerometer) or
  // D M R_bn m_n + o (magnetometer), with the noise covariance divided by `count`
  // (ml_data.hpp, decimation). M = I and count 1 are the single-sample updates above.
  InnovationTerm<T> updateAccelMean(const Eigen::Vector3d& accel_m_s2, const Eigen::Matrix3d& mean_rotation,
                                    double count) {
    const Mat3T<T> M = mean_rotation.cast<T>();
    const Vec3T<T> predicted = M * predictedAccel();
    return update(accel_m_s2.cast<T>() - predicted, M * accelJacobian(), model_.accel_cov / T(count));
  }
  InnovationTerm<T> updateMagMean(const Eigen::Vector3d& mag_unit, const Eigen::Matrix3d& mean_rotation, double count) {
    const Mat3T<T> M = mean_rotation.cast<T>();
    const Mat3T<T> r_bn = q_nb_.conjugate().toRotationMatrix();
    const Vec3T<T> predicted = model_.D * (M * (r_bn * model_.field_n)) + model_.offset;
    const Mat3T<T> H = model_.D * M * r_bn * crossMatrix<T>(model_.field_n);
    return update(mag_unit.cast<T>() - predicted, H, model_.mag_cov / T(count));
  }

  const QuatT<T>& attitude() const { return q_nb_; }
  const Mat3T<T>& covariance() const { return P_; }
  const MlModel<T>& model() const { return model_; }

 private:
  InnovationTerm<T> update(const Vec3T<T>& innovation, const Mat3T<T>& H, const Mat3T<T>& R) {
    using std::log;
    InnovationTerm<T> term;
    const Mat3T<T> PHt = P_ * H.transpose();
    Mat3T<T> S = H * PHt + R;
    S = T(0.5) * (S + S.transpose());
    Mat3T<T> L;
    if (!cholesky3<T>(S, L)) return term;
    const Mat3T<T> L_inv = lowerInverse<T>(L);
    term.normalised = L_inv * innovation;
    term.cost = T(0.5) * term.normalised.squaredNorm() + log(L(0, 0)) + log(L(1, 1)) + log(L(2, 2));
    const Mat3T<T> K = PHt * (L_inv.transpose() * L_inv);
    const Vec3T<T> eta = K * innovation;
    P_ -= K * PHt.transpose();
    P_ = T(0.5) * (P_ + P_.transpose());
    // Reset: move the linearisation point by η, the deviation returns to zero.
    q_nb_ = (quaternionFromRotationVector<T>(eta) * q_nb_).normalized();
    term.ok = true;
    return term;
  }

  MlModel<T> model_;
  Vec3T<T> gravity_n_;
  QuatT<T> q_nb_ = QuatT<T>::Identity();
  Mat3T<T> P_ = Mat3T<T>::Identity();
};

}  // namespace headingd::calib
