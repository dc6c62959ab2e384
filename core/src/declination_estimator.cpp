#include "headingd/core/declination_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

void CourseMinusHeading::add(double course_rad, double magnetic_heading_rad) {
  Direction* match = nullptr;
  for (auto& d : directions_) {
    if (std::abs(wrapAngle(course_rad - d.course.mean())) <= direction_width_rad_) match = &d;
  }
  if (match == nullptr) match = &directions_.emplace_back();
  match->course.add(course_rad);
  match->difference.add(wrapAngle(course_rad - magnetic_heading_rad));
  ++epochs_;
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
    variance_sum += d.difference.standardError() * d.difference.standardError();
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
