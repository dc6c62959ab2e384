#include "headingd/core/vertical_rate_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace headingd::core {

VerticalRateError::VerticalRateError(const EstimatorParams& p)
    : time_constant_s_(p.mag_rate_error_time_constant_s),
      observer_time_constant_s_(p.mag_heading_time_constant_s),
      max_turn_rad_s_(p.mag_rate_error_max_turn_rad_s),
      max_reference_age_s_(p.mag_rate_error_max_reference_age_s),
      max_set_aside_share_(p.mag_rate_error_max_set_aside_share),
      settle_s_(p.mag_rate_error_settle_s),
      steady_cos_(std::cos(p.mag_rate_error_steady_heading_rad)),
      max_rate_rad_s_(p.bias_max_rad_s),
      reference_age_s_(std::numeric_limits<double>::infinity()),
      set_aside_alpha_(p.mag_rate_error_settle_s) {}

void VerticalRateError::trackSteadyHeading(double dt_s, const Quat& q_nb) {
  // The x-axis heading as a horizontal direction (cos ψ, sin ψ) times a positive length (yawZyx's
  // atan2 arguments), compared with the anchor's by the angle between them: no atan2 per sample.
  steady_s_ += dt_s;
  const double w = q_nb.w(), x = q_nb.x(), y = q_nb.y(), z = q_nb.z();
  const Eigen::Vector2d heading(w * w + x * x - y * y - z * z, 2.0 * (x * y + w * z));
  // angle ≤ θ ⇔ a·h ≥ cos θ |a| |h|, squared to spare the roots (the anchor is a unit vector).
  const double along = steady_anchor_.dot(heading);
  const double bound_squared = steady_cos_ * steady_cos_ * heading.squaredNorm();
  const bool within = steady_cos_ >= 0.0 ? along >= 0.0 && along * along >= bound_squared
                                         : along >= 0.0 || along * along <= bound_squared;
  if (!within || !steady_anchored_) {
    steady_anchor_ = heading.normalized();
    steady_anchored_ = true;
    steady_s_ = 0.0;
  }
}

bool VerticalRateError::referenceIsRecent() const {
  return max_reference_age_s_ <= 0.0 || reference_age_s_ <= max_reference_age_s_;
}

void VerticalRateError::fieldSample(bool set_aside, double period_s) {
  if (time_constant_s_ <= 0.0 || !(period_s > 0.0)) return;
  field_seen_s_ += period_s;
  // The running mean of the shares at first (eq. 2.13 once that weighs less): a few clean
  // samples at the start are not yet a clean stretch, the steady-heading wait covers that.
  const double weight = startedLowPassWeight(field_seen_s_, period_s, 1.0 - set_aside_alpha_(period_s));
  set_aside_share_ += weight * ((set_aside ? 1.0 : 0.0) - set_aside_share_);
}

bool VerticalRateError::fieldIsClean() const { return referenceIsRecent() || set_aside_share_ < max_set_aside_share_; }

double VerticalRateError::learn(double innovation_rad, double dt_s, double turn_rate_rad_s) {
  if (time_constant_s_ <= 0.0 || turn_rate_rad_s > max_turn_rad_s_ || steady_s_ < settle_s_) return 0.0;
  if (!fieldIsClean()) return 0.0;
  // Ki = 1/(τ τ_i): the loop ψ̃'' + ψ̃'/τ + Ki ψ̃ = 0 has damping ratio ½ √(τ_i / τ).
  const double gain = dt_s / (observer_time_constant_s_ * time_constant_s_);
  rate_rad_s_ = std::clamp(rate_rad_s_ + innovation_rad * gain, -max_rate_rad_s_, max_rate_rad_s_);
  return gain;
}

}  // namespace headingd::core
