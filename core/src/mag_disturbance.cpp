#include "headingd/core/mag_disturbance.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

void MagDisturbanceDetector::setReference(double field_norm_uT, double inclination_rad) {
  has_reference_ = true;
  reference_norm_uT_ = field_norm_uT;
  reference_dip_rad_ = inclination_rad;
}

void MagDisturbanceDetector::restart() {
  direction_gyro_frame_.restart();
  direction_sensor_axes_ = LowPass<Vec3>(p_.time_constant_s);
}

MagDisturbance MagDisturbanceDetector::update(const Vec3& field_uT, double dip_rad, double dt_s) {
  const double norm = field_uT.norm();
  const bool has_directions = p_.residual_hard_iron_uT > 0.0 && norm > 0.0;
  if (has_directions) {
    const Vec3 direction = field_uT / norm;
    direction_turning_ = direction_gyro_frame_.add(direction, dt_s);
    direction_still_ = direction_sensor_axes_.update(direction, dt_s);
  }
  return test(norm, dip_rad, dt_s, has_directions);
}

double MagDisturbanceDetector::turnedAgainstField() const {
  const double sin_angle = direction_turning_.cross(direction_still_).norm();
  const double cos_angle = direction_turning_.dot(direction_still_);
  return sin_angle > 0.0 || cos_angle > 0.0 ? std::atan2(sin_angle, cos_angle) : 0.0;
}

double MagDisturbanceDetector::relativeThreshold(const NoiseFloor& floor, double configured) {
  // Until the floor is known (its first 2 s), the largest value it could give: at the
  // configured minimum a noisy magnetometer (1-1.5 µT per axis, phones) looked disturbed a
  // fifth to a half of the time then (simulated phone grade: 17-63 %), and a still block
  // without the field takes a hand's turn about the vertical for bias (rest_detector.hpp;
  // issue 28 item 3).
  const double maximum = 5.0 * configured;
  return std::isfinite(floor.value()) ? floor.threshold(4.0, configured, maximum) : maximum;
}

MagDisturbance MagDisturbanceDetector::test(double field_norm_uT, double dip_rad, double dt_s, bool has_directions) {
  // Deviations are taken against the low-pass *before* this sample enters it.
  norm_deviation_ = norm_lp_.initialised() ? std::abs(field_norm_uT - norm_lp_.value()) : 0.0;  // eq. 4.5
  dip_deviation_ = dip_lp_.initialised() ? std::abs(dip_rad - dip_lp_.value()) : 0.0;
  norm_lp_.update(field_norm_uT, dt_s);
  dip_lp_.update(dip_rad, dt_s);
  norm_floor_.update(std::sqrt(norm_deviation2_.update(norm_deviation_ * norm_deviation_, dt_s)), dt_s);
  dip_floor_.update(std::sqrt(dip_deviation2_.update(dip_deviation_ * dip_deviation_, dt_s)), dt_s);
  double norm_threshold = relativeThreshold(norm_floor_, p_.max_norm_deviation_uT);
  // The allowance, measured only where it may decide (an angle costs an atan2).
  turned_rad_ = 0.0;
  if (has_directions && norm_deviation_ > norm_threshold) {
    turned_rad_ = turnedAgainstField();
    norm_threshold += p_.residual_hard_iron_uT * turned_rad_;
  }
  const double dip_threshold = relativeThreshold(dip_floor_, p_.max_dip_deviation_rad);
  MagDisturbance d;
  d.norm_jump = norm_deviation_ > norm_threshold;
  d.dip_jump = dip_deviation_ > dip_threshold;
  if (p_.back_to_before_s > 0.0) {
    // The field as it was: the low-passes, once the relative tests have passed for a while
    // (a low-pass the disturbance has already moved is not "before").
    const bool jump = d.norm_jump || d.dip_jump;
    clean_s_ = jump ? 0.0 : clean_s_ + dt_s;
    if (clean_s_ >= p_.back_to_before_s) {
      has_before_ = true;
      before_norm_uT_ = norm_lp_.value();
      before_dip_rad_ = dip_lp_.value();
    }
    const bool back = jump && has_before_ && std::abs(field_norm_uT - before_norm_uT_) <= norm_threshold &&
                      std::abs(dip_rad - before_dip_rad_) <= dip_threshold;
    back_s_ = back ? back_s_ + dt_s : 0.0;
    if (back && back_s_ >= p_.back_to_before_s) {
      d.norm_jump = d.dip_jump = false;
      norm_lp_.reset(field_norm_uT);
      dip_lp_.reset(dip_rad);
      back_s_ = 0.0;
    }
  }
  testReference(d, dt_s);
  return d;
}

void MagDisturbanceDetector::testReference(MagDisturbance& d, double dt_s) {
  // On the low-passes: a steady offset, not single noisy samples.
  const auto against = [&](double norm_uT, double dip_rad) {
    d.norm_reference = std::abs(norm_lp_.value() - norm_uT) > p_.max_reference_norm_deviation_uT;
    d.dip_reference = std::abs(dip_lp_.value() - dip_rad) > p_.max_reference_dip_deviation_rad;
  };
  if (has_reference_) {
    against(reference_norm_uT_, reference_dip_rad_);
    return;
  }
  if (!(p_.learn_first_s > 0.0)) return;
  const bool homogeneous = !d.norm_jump && !d.dip_jump;
  if (!has_learned_) {
    learn_clean_s_ = homogeneous ? learn_clean_s_ + dt_s : 0.0;
    if (learn_clean_s_ < p_.learn_first_s) return;
    has_learned_ = true;
    learned_norm_uT_ = norm_lp_.value();
    learned_dip_rad_ = dip_lp_.value();
  }
  against(learned_norm_uT_, learned_dip_rad_);
  const bool different = d.norm_reference || d.dip_reference;
  different_s_ = different && homogeneous ? different_s_ + dt_s : 0.0;
  const bool follow = !different && homogeneous;
  if (follow || different_s_ >= p_.learn_new_s) {
    // Within the thresholds: follow the low-passes over learn_new_s; a different field that
    // stayed homogeneous that long: take it.
    const double w = different ? 1.0 : std::min(1.0, dt_s / std::max(p_.learn_new_s, dt_s));
    learned_norm_uT_ += w * (norm_lp_.value() - learned_norm_uT_);
    learned_dip_rad_ += w * (dip_lp_.value() - learned_dip_rad_);
    if (different) {
      different_s_ = 0.0;
      d.norm_reference = d.dip_reference = false;
    }
  }
}

}  // namespace headingd::core
