#include "headingd/core/rotated_field_update.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

void RotatedFieldUpdate::startBaseline(const Vec3& field, double noise, const Quat& gyro_frame_from_sensor) {
  start_field_ = field;
  start_noise_ = noise;
  integral_.start(gyro_frame_from_sensor);
  running_ = true;
}

bool RotatedFieldUpdate::update(GyroBiasEstimator& bias, const Vec3& field, const Quat& gyro_frame_from_sensor,
                                bool applies, double sample_noise) {
  if (!enabled() || !applies) {
    running_ = false;
    return false;
  }
  const double noise = std::max(sample_noise, p_.min_sample_noise);
  if (!running_) {
    startBaseline(field, noise, gyro_frame_from_sensor);
    return false;
  }
  if (integral_.intervalS() < p_.baseline_s) return false;
  // Eqs. 40-42 (44-46) over the baseline. Each end's noise is its own window's; the model takes
  // one σ for both, so the larger. What is fixed in sensor axes, r, errs by (I - Cᵀ) r, about
  // |r| times the angle turned: split over the model's two samples.
  const double turned_rad = Eigen::AngleAxisd(integral_.startFromEnd()).angle();
  const RotatedVectorModel model{
      std::hypot(std::max(noise, start_noise_), p_.residual_per_rad * turned_rad / std::sqrt(2.0))};
  NavigationState state;
  state.gyro_bias_rad_s = bias.bias();
  const bool applied = bias.addMeasurement(model.linearise(state, start_field_, field, integral_), p_.max_nis);
  ++(applied ? counters_.applied : counters_.rejected_by_gate);
  startBaseline(field, noise, gyro_frame_from_sensor);  // the next baseline starts at this sample
  return applied;
}

}  // namespace headingd::core
