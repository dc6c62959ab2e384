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
#include "headingd/core/measurement_model.hpp"

namespace headingd::core {

struct RotatedVectorModel {
  double noise_sigma;            // the vector sensor's white noise per axis and sample
  bool with_accel_bias = false;  // the accelerometer's vectors (AGU)

  // before, after: the vector at t and at t + interval_s (sensor axes); gyro_rad_s: the gyro's
  // mean reading over the interval, bias included.
  Linearised<3> linearise(const NavigationState& x, const Vec3& before, const Vec3& after, const Vec3& gyro_rad_s,
                          double interval_s) const;
};

}  // namespace headingd::core
