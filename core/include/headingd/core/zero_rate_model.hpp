#pragma once
// At rest the gyro reads its bias: y = b_g + n (the zero angular rate update; what the rest
// detector's still blocks measure, rest_detector.hpp). h = b̂_g, ∂h/∂δb_g = I.
#include "headingd/core/measurement_model.hpp"

namespace headingd::core {

struct ZeroRateModel {
  double noise_sigma_rad_s;  // the gyro's white noise per axis and sample

  Linearised<3> linearise(const NavigationState& x, const Vec3& gyro_rad_s) const;
};

}  // namespace headingd::core
