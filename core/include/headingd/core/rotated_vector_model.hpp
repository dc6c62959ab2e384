#pragma once
// A vector constant in the navigation frame, measured at two instants: its change in sensor
// axes is the sensor's rotation alone, which the gyro measures, so the pair observes the gyro's
// bias (and, for the specific force, the accelerometer's). MAGYQ's magnetic angular rate
// update (MARU, eqs. 39-43: the field during a quasi-static period, whatever its value) and
// acceleration gradient update (AGU, eqs. 44-46: the specific force during one).
//
// The sensor turns by the bias-corrected rate over the interval T, so a fixed vector turns the
// other way in its axes: with θ = -(ω_m - b_g) T (rad, sensor axes) and u = y(t) - b_a,
//   h = R(θ) u + b_a   (eq. 40 / 44; MAGYQ's accelerometer bias is a first-order Gauss-Markov
//                       process, eq. 45's (I - βT); over one sample interval it is taken as
//                       constant, β T ≈ 0)
//   ∂h/∂δb_g = -[R(θ) u]× J_l(θ) T   (exp(θ + T δb) ≈ exp(J_l T δb) exp(θ))
//   ∂h/∂δb_a = I - R(θ)
// and the residual y(t + T) - h. Both samples carry the sensor's noise: R = σ² (I + R Rᵀ) = 2σ² I
// (eq. 42 / 46's [I, -h2] applied to the two noises).
//
// MAGYQ takes the pair one sample apart, where the vector's change is the sample's noise many
// times over (a 50 µT field turned by a 10 mrad/s bias error moves 5 nT in 10 ms against
// 0.1-1.5 µT of noise). Over a longer baseline T the change grows with T and the noise does
// not, so the same model also takes the pair at the two ends of an interval over which the
// gyro's increments were composed (GyroRotationIntegral): with C the rotation from the end's
// sensor axes to the start's and u = y(t) - b_a,
//   h = Cᵀ u + b_a
//   ∂h/∂δb_g = -Cᵀ [u]× N,   N = ∫ C(τ) dτ over the interval
// (a bias error δb turns the sensor by δb dτ at each instant τ, in that instant's axes: N δb in
// the start's axes; over one sample C = R(-θ) and N = J_l(θ) T, the form above).
#include "headingd/core/measurement_model.hpp"

namespace headingd::core {

// The sensor's rotation over an interval as the bias-corrected gyro composes it, and N of the
// model above. Fed with the attitude in any frame the gyro alone carries (GyroFrame).
class GyroRotationIntegral {
 public:
  // The interval starts here: frame_from_sensor is the sensor's attitude in the gyro's frame now.
  void start(const Quat& frame_from_sensor);
  // The next gyro sample's attitude in the same frame, dt_s after the previous one.
  void add(const Quat& frame_from_sensor, double dt_s);

  double intervalS() const { return interval_s_; }
  // C: the end's sensor axes to the start's.
  const Mat3& startFromEnd() const { return start_from_end_; }
  // N = ∫ C(τ) dτ, by the trapezoid (second order in the turn per sample, as the gyro's own
  // composition of each sample's turn about its middle).
  const Mat3& biasTurn() const { return bias_turn_; }

 private:
  Quat start_inverse_ = Quat::Identity();
  Mat3 start_from_end_ = Mat3::Identity();
  Mat3 bias_turn_ = Mat3::Zero();
  double interval_s_ = 0.0;
};

struct RotatedVectorModel {
  double noise_sigma;            // the vector sensor's white noise per axis and sample
  bool with_accel_bias = false;  // the accelerometer's vectors (AGU)

  // before, after: the vector at t and at t + interval_s (sensor axes); gyro_rad_s: the gyro's
  // mean reading over the interval, bias included.
  Linearised<3> linearise(const NavigationState& x, const Vec3& before, const Vec3& after, const Vec3& gyro_rad_s,
                          double interval_s) const;
  // The same over an interval the gyro's increments were composed over (bias taken off with the
  // estimate of each instant, which x's bias is taken to be).
  Linearised<3> linearise(const NavigationState& x, const Vec3& before, const Vec3& after,
                          const GyroRotationIntegral& interval) const;
};

}  // namespace headingd::core
