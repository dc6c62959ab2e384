#pragma once
// The field, turned into NED by the attitude, points to magnetic north: the heading
// measurement of Henriksson's observer (eqs. 4.1-4.2; mag_heading_observer.hpp measures it).
// With m = R(q̂) y the measured field in NED, the model's value is m's azimuth,
//   h = atan2(m_e, m_n),  z = 0 (north),
// so the residual is -h, the turn that brings the heading to the field's. With q = exp(δθ) ⊗ q̂,
// m moves by δθ × m, and
//   ∂h/∂δθ = (-m_e, m_n, 0) / (m_n² + m_e²) · (-[m]×)
// which is 1 about down and, through the field's vertical part, -tan(dip) about the
// horizontal axis along the field (at the true heading: north): a tilt error moves the
// measured heading (the effect heading_uncertainty.hpp carries). Invalid (a zero Jacobian and an infinite noise) where
// the horizontal field is below min_horizontal_fraction of the field.
#include "headingd/core/measurement_model.hpp"

namespace headingd::core {

struct MagneticHeadingModel {
  double noise_sigma_rad;  // the heading measurement's noise
  double min_horizontal_fraction = 0.1;

  Linearised<1> linearise(const NavigationState& x, const Vec3& field_sensor_uT) const;
};

}  // namespace headingd::core
