#pragma once
// Orientation error split into heading and inclination, as BROAD scores it
// (Laidig et al. 2021, "BROAD—A Benchmark for Robust Inertial Orientation Estimation",
// Data 6(7):72, and its broad_utils.calculateRMSE).
#include <cstddef>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct OrientationError {
  double total_rad;
  double heading_rad;
  double inclination_rad;
};

// Error between an estimate q_nb (sensor → NED) and a reference q_ref_enu (sensor → ENU):
// q_err = nedToEnu(q_nb) ⊗ q_ref⁻¹ = (w, x, y, z); total 2·acos|w|, heading 2·atan|z/w|,
// inclination 2·acos √(w² + z²).
OrientationError orientationError(const Quat& q_nb, const Quat& q_ref_enu);

class RmseAccumulator {
 public:
  void add(const OrientationError& e);
  std::size_t count() const { return n_; }
  OrientationError rmse() const;  // NaN when empty

 private:
  std::size_t n_ = 0;
  double sum_total_ = 0.0, sum_heading_ = 0.0, sum_inclination_ = 0.0;
};

}  // namespace headingd::core
