#include "headingd/core/magnetic_attitude_update.hpp"

#include <cmath>

#include "headingd/core/reference_vector_model.hpp"

namespace headingd::core {

void MagneticAttitudeUpdate::setReference(double field_norm_uT, double inclination_rad) {
  if (!(field_norm_uT > 0.0) || !std::isfinite(inclination_rad)) return;
  reference_ned_uT_ = field_norm_uT * Vec3(std::cos(inclination_rad), 0.0, std::sin(inclination_rad));
  has_reference_ = true;
}

bool MagneticAttitudeUpdate::update(AttitudeEkf& ekf, const Vec3& field_uT, double field_period_s,
                                    double heading_sigma_rad) {
  since_update_s_ += field_period_s;
  // (1e-9 s: ten samples of 0.1 s sum to a hair below 1 s.)
  if (!enabled() || !has_reference_ || since_update_s_ < p_.interval_s - 1e-9) return false;
  since_update_s_ = 0.0;
  const ReferenceVectorModel model{reference_ned_uT_, p_.noise_uT};
  NavigationState state;
  state.q_nb = ekf.attitude();
  const AttitudeEkf before = ekf;
  const AttitudeUpdateResult result =
      ekf.update(model.linearise(state, field_uT), heading_sigma_rad, AttitudeAxes{}, p_.max_nis);
  if (!result.applied) {
    ++counters_.rejected_by_gate;
    return false;
  }
  // The magnetic frame's check: the measured field's direction against the one the corrected
  // attitude predicts (the header says why that is the three-rotation comparison at its best A).
  const Vec3 predicted = ekf.attitude().conjugate() * reference_ned_uT_;
  const double angle = std::atan2(predicted.cross(field_uT).norm(), predicted.dot(field_uT));
  if (!(angle <= p_.verify_max_rad)) {
    ekf = before;
    ++counters_.rejected_by_verification;
    return false;
  }
  ++counters_.applied;
  return true;
}

}  // namespace headingd::core
