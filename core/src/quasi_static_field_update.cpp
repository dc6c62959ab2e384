#include "headingd/core/quasi_static_field_update.hpp"

#include <cmath>

#include "headingd/core/reference_vector_model.hpp"

namespace headingd::core {

double QuasiStaticFieldUpdate::update(AttitudeEkf& ekf, const Vec3& field_uT, const Quat& gyro_frame_from_sensor,
                                      bool in_period, bool set_aside, double field_period_s, double rate_sigma_rad_s) {
  if (!enabled() || !in_period) {
    has_reference_ = false;
    return 0.0;
  }
  if (!has_reference_) {
    // Eq. 35's reference: the field at the period's start in the navigation frame.
    reference_ned_uT_ = ekf.attitude() * field_uT;
    start_attitude_ = ekf.attitude();
    start_gyro_frame_ = gyro_frame_from_sensor;
    heading_corrected_rad_ = 0.0;
    drift_sigma_rad_ = 0.0;
    has_reference_ = true;
    return 0.0;
  }
  // The gyro's rate error is mostly a bias: the drift's sigma grows by σ_b per second, from what
  // the last update left of it.
  drift_sigma_rad_ += rate_sigma_rad_s * field_period_s;
  if (!set_aside) return 0.0;
  // The attitude the reference is compared through: the start's, carried by the gyro alone and
  // turned by what this update corrected since. Not the EKF's own: gravity keeps correcting its
  // tilt while the person stands, and a tilt change δ moves the reference's horizontal part by
  // δ·tan(dip) (1.7° of heading per 0.5° at 73° dip), which the update would take for heading drift.
  NavigationState state;
  state.q_nb = (headingRotation(heading_corrected_rad_) * start_attitude_ * start_gyro_frame_.conjugate() *
                gyro_frame_from_sensor)
                   .normalized();
  const double turned_rad = state.q_nb.angularDistance(start_attitude_);
  const double residual_uT = p_.residual_hard_iron_uT * turned_rad;
  const ReferenceVectorModel model{reference_ned_uT_, std::hypot(p_.noise_uT, residual_uT)};
  const AttitudeUpdateResult result = ekf.update(model.linearise(state, field_uT), drift_sigma_rad_,
                                                 AttitudeAxes{.tilt = false, .heading = true}, p_.max_nis);
  if (!result.applied) {
    ++counters_.rejected_by_gate;
    return 0.0;
  }
  ++counters_.applied;
  drift_sigma_rad_ = std::sqrt(result.heading_variance_rad2);
  heading_corrected_rad_ += result.turn_rad.z();
  return result.turn_rad.z();
}

}  // namespace headingd::core
