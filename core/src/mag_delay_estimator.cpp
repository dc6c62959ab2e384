#include "headingd/core/mag_delay_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

void MagDelayEstimator::update(const Vec3& gyro_rad_s, const Vec3* mag_uT, bool clean, double dt_s) {
  if (p_.max_delay_s <= 0.0) return;
  // The held time: a sample equal to the last one seen is the magnetometer's last update
  // repeated (a noisy sensor never repeats itself bit for bit).
  const bool fresh = mag_uT != nullptr && *mag_uT != last_seen_;
  if (mag_uT != nullptr) {
    held_s_ = fresh ? 0.0 : held_s_ + dt_s;
    last_seen_ = *mag_uT;
  }
  if (mag_uT == nullptr || !clean) {
    has_previous_ = false;
    return;
  }
  // The regressor ∫ ω̇ × m dt (what a late field differs by is Δ times it), and the field as
  // the gyro says it turned over this interval (ṁ = -ω × m, to second order).
  if (has_previous_) regressor_ += (gyro_rad_s - previous_gyro_).cross(predicted_);
  previous_gyro_ = gyro_rad_s;
  predicted_ = turnedBySmallAngle(predicted_, -gyro_rad_s * dt_s);
  if (!fresh) return;

  if (has_previous_) {
    const Vec3 residual = *mag_uT - predicted_;  // ρ
    const double decay = decay_(dt_s);
    sum_xy_ = decay * sum_xy_ + residual.dot(regressor_);
    sum_xx_ = decay * sum_xx_ + regressor_.squaredNorm();
    sum_yy_ = decay * sum_yy_ + residual.squaredNorm();
    count_ = decay * count_ + 1.0;
    if (sum_xx_ > 0.0 && count_ > 3.0) {  // a spread from a handful of samples at least
      estimate_s_ = sum_xy_ / sum_xx_;
      // Residual variance per sample (3 components, one parameter), over the information.
      const double residual_ss = std::max(sum_yy_ - estimate_s_ * sum_xy_, 0.0);
      sigma_s_ = std::sqrt(residual_ss / (3.0 * count_ - 1.0) / sum_xx_);
      candidate_s_ =
          sigma_s_ < p_.apply_below_sigma_s ? std::clamp(estimate_s_, -p_.max_delay_s, p_.max_delay_s) : 0.0;
    }
  }
  predicted_ = *mag_uT;
  regressor_ = Vec3::Zero();
  has_previous_ = true;
}

void MagDelayEstimator::scoreDip(const Vec3& down_s, const Vec3& mag_default, const Vec3& mag_delayed, bool clean,
                                 double dt_s) {
  if (!clean) return;
  const double norm_default = mag_default.norm(), norm_delayed = mag_delayed.norm();
  if (!(norm_default > 0.0) || !(norm_delayed > 0.0)) return;
  const double sin_dip[2] = {down_s.dot(mag_default) / norm_default, down_s.dot(mag_delayed) / norm_delayed};
  const double decay = decay_(dt_s);
  dip_weight_ = decay * dip_weight_ + 1.0;
  double spread[2];
  for (int i = 0; i < 2; ++i) {
    dip_sum_[i] = decay * dip_sum_[i] + sin_dip[i];
    dip_sum_sq_[i] = decay * dip_sum_sq_[i] + sin_dip[i] * sin_dip[i];
    const double mean = dip_sum_[i] / dip_weight_;
    spread[i] = dip_sum_sq_[i] / dip_weight_ - mean * mean;
  }
  use_candidate_ = spread[1] < spread[0];
}

}  // namespace headingd::core
