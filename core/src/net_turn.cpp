#include "headingd/core/net_turn.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {

double NetTurn::update(const Quat& q_nb, double dt_s) {
  if (!started_) {
    mean_ = last_counted_ = q_nb.normalized();
    started_ = true;
    return 0.0;
  }
  // q and -q are the same attitude: average the one on the mean's side.
  const double sign = mean_.coeffs().dot(q_nb.coeffs()) < 0.0 ? -1.0 : 1.0;
  mean_.coeffs() += (1.0 - decay_(dt_s)) * (sign * q_nb.coeffs() - mean_.coeffs());
  mean_.normalize();
  const double angle = 2.0 * std::asin(std::min(1.0, (last_counted_.conjugate() * mean_).vec().norm()));
  if (angle < step_rad_) return 0.0;
  last_counted_ = mean_;
  return angle;
}

}  // namespace headingd::core
