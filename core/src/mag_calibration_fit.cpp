#include "headingd/core/mag_calibration_fit.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

void MagCalibrationFit::Strength::update(double norm, double dt_s) {
  const double m = mean.update(norm, dt_s);  // the first sample initialises both to no deviation
  const double relative = (norm - m) / std::max(m, 1e-9);
  variance.update(relative * relative, dt_s);
}

double MagCalibrationFit::rawFluctuation() const { return std::sqrt(raw_.variance.value()); }
double MagCalibrationFit::calibratedFluctuation() const { return std::sqrt(calibrated_.variance.value()); }

bool MagCalibrationFit::fitsBetter(const Strength& other, const Strength& in_use) const {
  const double floor = p_.min_relative_fluctuation * p_.min_relative_fluctuation;
  const double in_use_variance = in_use.variance.value(), other_variance = other.variance.value();
  if (in_use_variance > floor && in_use_variance > p_.variance_ratio * other_variance) return true;
  if (!(expected_norm_uT_ > 0.0)) return false;
  const double in_use_error = std::abs(in_use.mean.value() / expected_norm_uT_ - 1.0);
  const double other_error = std::abs(other.mean.value() / expected_norm_uT_ - 1.0);
  return in_use_error > p_.max_relative_strength_error && other_error < p_.strength_error_ratio * in_use_error;
}

bool MagCalibrationFit::update(const Vec3& raw_uT, const Vec3& calibrated_uT, double dt_s) {
  const double raw_norm = raw_uT.norm(), calibrated_norm = calibrated_uT.norm();
  if (!std::isfinite(raw_norm) || !std::isfinite(calibrated_norm) || !(dt_s >= 0.0)) return calibrated_in_use_;
  // A clock jump must not wipe the history in one step.
  raw_.update(raw_norm, std::min(dt_s, 1.0));
  calibrated_.update(calibrated_norm, std::min(dt_s, 1.0));

  const Strength& in_use = calibrated_in_use_ ? calibrated_ : raw_;
  const Strength& other = calibrated_in_use_ ? raw_ : calibrated_;
  other_better_s_ = fitsBetter(other, in_use) ? other_better_s_ + dt_s : 0.0;
  if (other_better_s_ >= p_.confirm_s) {
    calibrated_in_use_ = !calibrated_in_use_;
    ++(calibrated_in_use_ ? taken_back_ : set_aside_);
    other_better_s_ = 0.0;
  }
  return calibrated_in_use_;
}

}  // namespace headingd::core
