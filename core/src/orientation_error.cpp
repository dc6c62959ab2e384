#include "headingd/core/orientation_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace headingd::core {

OrientationError orientationError(const Quat& q_nb, const Quat& q_ref_enu) {
  const Quat e = (nedToEnu(q_nb.normalized()) * q_ref_enu.normalized().inverse()).normalized();
  const double w = std::abs(e.w());
  const double z = std::abs(e.z());
  return {2.0 * std::acos(std::min(1.0, w)), 2.0 * std::atan2(z, w),
          2.0 * std::acos(std::min(1.0, std::sqrt(w * w + z * z)))};
}

void RmseAccumulator::add(const OrientationError& e) {
  ++n_;
  sum_total_ += e.total_rad * e.total_rad;
  sum_heading_ += e.heading_rad * e.heading_rad;
  sum_inclination_ += e.inclination_rad * e.inclination_rad;
}

OrientationError RmseAccumulator::rmse() const {
  if (n_ == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  const double n = static_cast<double>(n_);
  return {std::sqrt(sum_total_ / n), std::sqrt(sum_heading_ / n), std::sqrt(sum_inclination_ / n)};
}

}  // namespace headingd::core
