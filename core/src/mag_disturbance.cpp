#include "headingd/core/mag_disturbance.hpp"

#include <cmath>

namespace headingd::core {

bool MagDisturbanceDetector::update(double field_norm_uT, double dip_rad, double dt_s) {
  // Deviations are taken against the low-pass *before* this sample enters it.
  norm_deviation_ = norm_lp_.initialised() ? std::abs(field_norm_uT - norm_lp_.value()) : 0.0;  // eq. 4.5
  dip_deviation_ = dip_lp_.initialised() ? std::abs(dip_rad - dip_lp_.value()) : 0.0;
  norm_lp_.update(field_norm_uT, dt_s);
  dip_lp_.update(dip_rad, dt_s);
  return norm_deviation_ > p_.max_norm_deviation_uT || dip_deviation_ > p_.max_dip_deviation_rad;
}

}  // namespace headingd::core
