#pragma once
// The exact gradient of the ML cost (Kok & Schön 2016 eq. 6) by reverse-mode differentiation
// (ml_reverse_scalar.hpp) through the EKF of ml_likelihood.hpp, one step at a time: all 34
// derivatives for about 20 cost evaluations' worth of work, where the Jets take some 65 and
// forward differences 35. Same value and gradient as the Jets.
#include "headingd/calib/ml/ml_data.hpp"
#include "headingd/calib/ml/ml_parameters.hpp"

namespace headingd::calib {

// Cost of eq. 6 at θ and, when `gradient` is not null, dcost/dθ. False where
// mlNegativeLogLikelihood fails. Thread-safe (one tape per thread).
bool mlCostWithAdjointGradient(const MlData& data, const double* theta, double& cost, double* gradient);

}  // namespace headingd::calib
