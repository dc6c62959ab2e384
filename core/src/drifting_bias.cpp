#include "headingd/core/drifting_bias.hpp"

#include <cmath>

namespace headingd::core {

DriftingBias::DriftingBias(const Params& p) : p_(p) {
  P_.topLeftCorner<3, 3>() = p.initial_variance * Mat3::Identity();
  P_.bottomRightCorner<3, 3>() = p.instability_rad_s * p.instability_rad_s * Mat3::Identity();  // stationary
}

void DriftingBias::predict(double dt_s) {
  const double growth = p_.walk_rad_s_per_sqrt_s * p_.walk_rad_s_per_sqrt_s * dt_s;
  for (int i = 0; i < 3; ++i) {
    if (P_(i, i) < p_.initial_variance) P_(i, i) += growth;
  }
  if (p_.instability_rad_s <= 0.0) return;
  if (dt_s != decay_dt_s_) {  // the IMU's period, nearly always the last one
    decay_dt_s_ = dt_s;
    decay_ = std::exp(-dt_s / p_.instability_time_s);
  }
  const double decay = decay_;
  x_.tail<3>() *= decay;
  P_.bottomRows<3>() *= decay;  // g's rows and columns; its own block twice
  P_.rightCols<3>() *= decay;
  P_.bottomRightCorner<3, 3>().diagonal().array() +=
      p_.instability_rad_s * p_.instability_rad_s * (1.0 - decay * decay);
}

Mat3 DriftingBias::covariance() const {
  const Eigen::Matrix<double, 6, 3> cross = sumCrossCovariance();
  return cross.topRows<3>() + cross.bottomRows<3>();
}

void DriftingBias::clampTo(double max_rad_s) {
  const Vec3 b = bias();
  const double norm = b.norm();
  if (norm > max_rad_s) x_.head<3>() = b * (max_rad_s / norm) - x_.tail<3>();
}

}  // namespace headingd::core
