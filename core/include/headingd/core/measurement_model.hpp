#pragma once
// What every measurement model shares (issue 29, item 1): the state a model is linearised
// about, the error state its Jacobian is taken in, and the result a filter needs from it, its
// residual, Jacobian and noise. Each measurement is then a small type of its own with one
// `linearise` (reference_vector_model.hpp, rotated_vector_model.hpp, zero_rate_model.hpp,
// magnetic_heading_model.hpp), checked against a numerical Jacobian in its test, and a filter
// can take any of them through one update without knowing which exist (as Ceres' cost
// functions and GTSAM's factors are to their solvers; DESIGN.md, "Estimator direction").
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// The estimate a model is linearised about.
struct NavigationState {
  Quat q_nb = Quat::Identity();         // sensor to NED (the heading from magnetic north)
  Vec3 gyro_bias_rad_s = Vec3::Zero();  // what the gyro reads at rest, sensor axes
  Vec3 accel_bias_m_s2 = Vec3::Zero();  // what the accelerometer reads beyond the specific force
};

// The error state: 9 numbers. The attitude's error is a turn about the NED axes,
// q = exp(δθ) ⊗ q̂ (as AttitudeEkf carries its covariance: a tilt about north and east, a
// heading about down); the biases' errors are differences, b = b̂ + δb.
namespace error_state {
constexpr int kAttitude = 0;   // δθ, rad about NED north, east, down
constexpr int kGyroBias = 3;   // δb_g, rad/s, sensor axes
constexpr int kAccelBias = 6;  // δb_a, m/s², sensor axes
constexpr int kSize = 9;
}  // namespace error_state
using ErrorVector = Eigen::Matrix<double, error_state::kSize, 1>;

// x̂ moved by δx as the error state defines it.
NavigationState perturbed(const NavigationState& x, const ErrorVector& dx);

// One measurement's linearisation about x̂: z - h(x̂ ⊕ δx) ≈ residual - jacobian δx, with the
// measurement's noise covariance R.
template <int N>
struct Linearised {
  Eigen::Matrix<double, N, 1> residual = Eigen::Matrix<double, N, 1>::Zero();  // z - h(x̂)
  Eigen::Matrix<double, N, error_state::kSize> jacobian =
      Eigen::Matrix<double, N, error_state::kSize>::Zero();  // ∂h/∂δx at x̂
  Eigen::Matrix<double, N, N> noise_covariance = Eigen::Matrix<double, N, N>::Identity();
};

// The rotation of a rotation vector φ as a matrix, and SO(3)'s left Jacobian there:
// exp(φ + δ) ≈ exp(J_l(φ) δ) exp(φ) (Barfoot, State Estimation for Robotics, eq. 7.77a).
Mat3 rotationMatrix(const Vec3& rotation_vector);
Mat3 so3LeftJacobian(const Vec3& rotation_vector);

}  // namespace headingd::core
