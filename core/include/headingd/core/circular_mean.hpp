#pragma once
// Mean of angles on the circle (Henriksson eqs. 5.1-5.2 average angle differences; done as
// plain arithmetic means they break at ±180°, so the mean is taken of unit vectors).
#include <cmath>
#include <cstddef>

namespace headingd::core {

class CircularMean {
 public:
  void add(double angle_rad, double weight = 1.0) {
    sum_cos_ += weight * std::cos(angle_rad);
    sum_sin_ += weight * std::sin(angle_rad);
    sum_weight_ += weight;
    ++count_;
  }
  std::size_t count() const { return count_; }
  double weight() const { return sum_weight_; }
  double mean() const { return std::atan2(sum_sin_, sum_cos_); }
  // Mean resultant length R in [0, 1]: 1 when all angles agree.
  double resultantLength() const { return sum_weight_ > 0.0 ? std::hypot(sum_cos_, sum_sin_) / sum_weight_ : 0.0; }
  // Circular standard deviation sqrt(-2 ln R) (equals the ordinary one for small spreads).
  double spread() const {
    const double r = resultantLength();
    if (r >= 1.0) return 0.0;  // identical angles (or rounding just above 1)
    return r > 0.0 ? std::sqrt(-2.0 * std::log(r)) : INFINITY;
  }
  // Standard error of the mean, treating the samples as independent.
  double standardError() const { return count_ > 1 ? spread() / std::sqrt(static_cast<double>(count_)) : INFINITY; }

 private:
  double sum_cos_ = 0.0, sum_sin_ = 0.0, sum_weight_ = 0.0;
  std::size_t count_ = 0;
};

}  // namespace headingd::core
