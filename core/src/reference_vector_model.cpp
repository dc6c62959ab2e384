#include "headingd/core/reference_vector_model.hpp"

namespace headingd::core {

Linearised<3> ReferenceVectorModel::linearise(const NavigationState& x, const Vec3& measured) const {
  const Mat3 earth_to_sensor = x.q_nb.conjugate().toRotationMatrix();
  Vec3 expected = earth_to_sensor * reference_ned;
  Linearised<3> l;
  // exp(δθ) turns r, as the sensor sees it, by -δθ: R̂ᵀ (r - δθ × r) = h + R̂ᵀ [r]× δθ.
  l.jacobian.block<3, 3>(0, error_state::kAttitude) = earth_to_sensor * crossMatrix(reference_ned);
  if (with_accel_bias) {
    expected += x.accel_bias_m_s2;
    l.jacobian.block<3, 3>(0, error_state::kAccelBias).setIdentity();
  }
  l.residual = measured - expected;
  l.noise_covariance = noise_sigma * noise_sigma * Mat3::Identity();
  return l;
}

}  // namespace headingd::core
