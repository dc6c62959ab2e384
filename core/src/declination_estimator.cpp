#include "headingd/core/declination_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

void CourseMinusHeading::add(double course_rad, double magnetic_heading_rad, bool follows_previous) {
  const double difference = wrapAngle(course_rad - magnetic_heading_rad);
  std::optional<std::size_t> index;
  for (std::size_t i = 0; i < directions_.size(); ++i) {
    if (std::abs(wrapAngle(course_rad - directions_[i].course.mean())) <= direction_width_rad_) index = i;
  }
  if (!index) {
    index = directions_.size();
    directions_.emplace_back().reference_rad = difference;
  }
  if (!follows_previous || last_direction_ != index) {
    for (auto& d : directions_) d.previous.reset();
  }
  Direction* match = &directions_[*index];
  match->course.add(course_rad);
  match->difference.add(difference);
  const double deviation = wrapAngle(difference - match->reference_rad);
  match->sum += deviation;
  match->sum_squares += deviation * deviation;
  if (match->previous) {
    match->lag_products += deviation * *match->previous;
    match->lag_sum_current += deviation;
    match->lag_sum_previous += *match->previous;
    ++match->lag_pairs;
  }
  match->previous = deviation;
  last_direction_ = index;
  ++epochs_;
}

double CourseMinusHeading::Direction::standardError() const {
  const double n = static_cast<double>(difference.count());
  if (n < 2.0) return std::numeric_limits<double>::infinity();
  const double mean = sum / n;
  const double variance = std::max(sum_squares / n - mean * mean, 0.0);
  // Consecutive differences share the receiver's velocity error (a u-blox-class receiver's
  // is correlated over seconds), so n epochs hold fewer independent ones: the variance of
  // their mean grows by (1 + ρ)/(1 - ρ) for a lag-1 correlation ρ (first-order Gauss-Markov).
  // ρ is clamped to [0, 0.8] (at most 3× the independent σ) against a noisy estimate.
  double rho = 0.0;
  if (lag_pairs >= 5 && variance > 0.0) {
    const double pairs = static_cast<double>(lag_pairs);
    const double covariance = lag_products / pairs - (lag_sum_current / pairs) * (lag_sum_previous / pairs);
    rho = std::clamp(covariance / variance, 0.0, 0.8);
  }
  return std::sqrt(variance / n * (1.0 + rho) / (1.0 - rho));
}

int CourseMinusHeading::directions() const {
  int n = 0;
  for (const auto& d : directions_) n += d.difference.count() >= static_cast<std::size_t>(min_direction_epochs_);
  return n;
}

bool CourseMinusHeading::estimate(AngleEstimate* out) const {
  CircularMean over_directions;  // eq. 5.1
  double variance_sum = 0.0;
  int n = 0;
  for (const auto& d : directions_) {
    if (d.difference.count() < static_cast<std::size_t>(min_direction_epochs_)) continue;
    over_directions.add(d.difference.mean());
    variance_sum += d.standardError() * d.standardError();
    ++n;
  }
  if (n == 0) return false;
  out->value_rad = over_directions.mean();
  // The mean of n direction means: its variance is the sum of theirs over n².
  out->sigma_rad = std::sqrt(variance_sum) / n;
  return true;
}

AngleEstimate fuseAngles(std::span<const AngleEstimate> estimates) {
  if (estimates.empty()) return {0.0, std::numeric_limits<double>::infinity()};
  const double about = estimates.front().value_rad;
  double weight_sum = 0.0, weighted = 0.0;
  for (const auto& e : estimates) {
    const double sigma = std::max(e.sigma_rad, 1e-9);  // a perfect source must not give ∞/∞
    const double w = 1.0 / (sigma * sigma);
    weight_sum += w;
    weighted += w * wrapAngle(e.value_rad - about);
  }
  return {wrapAngle(about + weighted / weight_sum), 1.0 / std::sqrt(weight_sum)};
}

}  // namespace headingd::core
