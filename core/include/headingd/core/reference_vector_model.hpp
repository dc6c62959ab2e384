#pragma once
// A vector known in the navigation frame, measured in sensor axes: y = R(q)ᵀ r + b + n, with
// b the accelerometer's bias where the sensor is the accelerometer. One model for three
// measurements that differ only in where r comes from:
//  - gravity: r = (0, 0, -g), the specific force at rest (Henriksson eq. 3.5, the EKF's
//    update; MAGYQ's global case of eqs. 35-36);
//  - the QSF updates (MAGYQ eqs. 35-38): r the field, or the specific force, of the
//    quasi-static period's first samples (quasi_static_field.hpp) turned into NED by the
//    attitude then; it holds the attitude to the period's start, whatever the field's value;
//  - MAU (Khedr, Radi & El-Sheimy, the magnetometer against the World Magnetic Model in the
//    local level frame): r the model's field at the place, in the filter's NED (whose north
//    is magnetic: the declination turned out), observing roll and pitch as well as azimuth.
// Linearised about q̂ with q = exp(δθ) ⊗ q̂ (measurement_model.hpp):
//   h = R̂ᵀ r + b,   ∂h/∂δθ = R̂ᵀ [r]×,   ∂h/∂δb_a = I (accelerometer only).
#include "headingd/core/measurement_model.hpp"

namespace headingd::core {

struct ReferenceVectorModel {
  Vec3 reference_ned;            // r: µT for a field, m/s² for a specific force
  double noise_sigma;            // the measurement's white noise per axis, same unit
  bool with_accel_bias = false;  // the accelerometer's measurement: its bias is part of h

  Linearised<3> linearise(const NavigationState& x, const Vec3& measured) const;
};

}  // namespace headingd::core
