#include "headingd/core/vector_delay_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

void VectorDelayEstimator::update(const Vec3& gyro_rad_s, const Vec3* sample, bool clean, double dt_s) {
  if (p_.max_delay_s <= 0.0) return;
  // The held time: a sample equal to the last one seen is the sensor's last update repeated
  // (a noisy sensor never repeats itself bit for bit).
  const bool fresh = sample != nullptr && (!p_.repeats_are_holds || *sample != last_seen_);
  if (sample != nullptr) {
    held_s_ = fresh ? 0.0 : held_s_ + dt_s;
    if (p_.repeats_are_holds) last_seen_ = *sample;
  }
  if (sample == nullptr || !clean) {
    has_previous_ = false;
    return;
  }
  // The vector and the rate at the chain's start as the gyro says they turned over this
  // interval (v̇ = -ω × v, to second order): at the chain's end, what a late vector differs by
  // is Δ (ω₂ - ω₁) × v₂, ω₁ and v₂ both in the end's axes.
  predicted_ = turnedBySmallAngle(predicted_, -gyro_rad_s * dt_s);
  start_rate_ = turnedBySmallAngle(start_rate_, -gyro_rad_s * dt_s);
  chain_s_ += dt_s;
  // A chain ends at a fresh sample once it spans min_span_s: ∫ ω̇ dt is the change of the rate
  // over the chain, whose signal grows with its span while the gyro's noise in it does not
  // (over one row a noisy gyro's difference is mostly noise, which biases Δ̂ towards zero).
  if (!fresh || (has_previous_ && chain_s_ < p_.min_span_s)) return;

  if (has_previous_) {
    const Vec3 residual = *sample - predicted_;  // ρ
    const Vec3 regressor = (gyro_rad_s - start_rate_).cross(predicted_);
    const double decay = chain_decay_(chain_s_);
    sum_xy_ = decay * sum_xy_ + residual.dot(regressor);
    sum_xx_ = decay * sum_xx_ + regressor.squaredNorm();
    sum_yy_ = decay * sum_yy_ + residual.squaredNorm();
    count_ = decay * count_ + 1.0;
    if (sum_xx_ > 0.0 && count_ > 3.0) {  // a spread from a handful of samples at least
      estimate_s_ = sum_xy_ / sum_xx_;
      // Residual variance per sample (3 components, one parameter), over the information.
      const double residual_ss = std::max(sum_yy_ - estimate_s_ * sum_xy_, 0.0);
      sigma_s_ = std::sqrt(residual_ss / (3.0 * count_ - 1.0) / sum_xx_);
      candidate_s_ = sigma_s_ < p_.apply_below_sigma_s ? std::clamp(estimate_s_, -p_.max_delay_s, p_.max_delay_s) : 0.0;
    }
  }
  predicted_ = *sample;
  start_rate_ = gyro_rad_s;
  chain_s_ = 0.0;
  has_previous_ = true;
}

void VectorDelayEstimator::scoreDownAngle(const Vec3& down_s, const Vec3& turned_default, const Vec3& turned_delayed,
                                          bool clean, double dt_s) {
  if (!clean) return;
  const double norm_default = turned_default.norm(), norm_delayed = turned_delayed.norm();
  if (!(norm_default > 0.0) || !(norm_delayed > 0.0)) return;
  const double cos_angle[2] = {down_s.dot(turned_default) / norm_default, down_s.dot(turned_delayed) / norm_delayed};
  const double decay = decay_(dt_s);
  angle_weight_ = decay * angle_weight_ + 1.0;
  double spread[2];
  for (int i = 0; i < 2; ++i) {
    cos_sum_[i] = decay * cos_sum_[i] + cos_angle[i];
    cos_sum_sq_[i] = decay * cos_sum_sq_[i] + cos_angle[i] * cos_angle[i];
    const double mean = cos_sum_[i] / angle_weight_;
    spread[i] = cos_sum_sq_[i] / angle_weight_ - mean * mean;
  }
  use_candidate_ = spread[1] < spread[0];
}

}  // namespace headingd::core
