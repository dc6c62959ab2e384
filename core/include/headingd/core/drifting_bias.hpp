#pragma once
// A gyro bias as a MEMS gyro's bias behaves over minutes, for the Kalman filter that estimates
// it (gyro_bias_estimator.hpp): the sum of two parts, carried as six states with one joint
// covariance.
//  - c, a constant that wanders as a random walk (rate random walk, temperature): its
//    variance grows by walk² dt, up to what nothing at all is known;
//  - g, a first-order Gauss-Markov process of standard deviation σ and correlation time τ,
//    ġ = -g/τ + n: the flat floor of an Allan-deviation plot, the bias instability (MAGYQ,
//    Renaudin & Combettes 2014, §3.2.3 and Table 2: 1.05-1.21 mrad/s for a phone's gyro; §3.2.2
//    models its accelerometer's bias this way). Per step g ← e^(-dt/τ) g, its variance
//    relaxing towards σ².
// A walk alone that covers the instability over tens of seconds would claim far too little
// over minutes, and one that fits minutes claims too much over seconds: over T without a
// measurement the instability adds 2σ²(1 - e^(-T/τ)), a walk w² T. Measurements see only
// the sum b = c + g (H = [I I]): the split between the parts comes out of the covariance.
// With σ = 0 the filter is the walk alone, exactly.
#include <Eigen/Core>
#include <Eigen/LU>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class DriftingBias {
 public:
  struct Params {
    double walk_rad_s_per_sqrt_s = 0.0;  // c's random walk
    double instability_rad_s = 0.0;      // g's σ
    double instability_time_s = 1.0;     // g's τ
    double initial_variance = 0.0;       // c's per axis, before anything is known; also its cap
  };
  explicit DriftingBias(const Params& p);

  // dt_s passes without a measurement.
  void predict(double dt_s);

  Vec3 bias() const { return x_.head<3>() + x_.tail<3>(); }
  // The covariance of the sum c + g.
  Mat3 covariance() const;

  // A measurement of M linear functions of the bias, y = H b + noise: `innovation` = y - H b̂,
  // S = H covariance() Hᵀ + the measurement's covariance (the caller's to weigh).
  template <int M>
  void correct(const Eigen::Matrix<double, M, 3>& H, const Eigen::Matrix<double, M, M>& S,
               const Eigen::Matrix<double, M, 1>& innovation) {
    const Eigen::Matrix<double, 6, M> PHt = sumCrossCovariance() * H.transpose();
    const Eigen::Matrix<double, 6, M> K = PHt * S.inverse();
    x_ += K * innovation;
    P_ -= K * PHt.transpose();
    P_ = 0.5 * (P_ + P_.transpose());
  }

  // The bias has changed by about `change` (a step the measurements showed): the constant part
  // becomes that much less certain.
  void openUp(const Vec3& change) { P_.topLeftCorner<3, 3>() += change * change.transpose(); }

  // The same sensor with its rate's sign turned (time run backwards: the offline smoother's
  // second filter): the bias turns sign, its uncertainty stays.
  void negate() { x_ = -x_; }

  // Keeps |b̂| at most max_rad_s, by moving the constant part.
  void clampTo(double max_rad_s);

 private:
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  // Cov(x, c + g) = P [I; I].
  Eigen::Matrix<double, 6, 3> sumCrossCovariance() const { return P_.leftCols<3>() + P_.rightCols<3>(); }

  Params p_;
  Vec6 x_ = Vec6::Zero();  // c, then g
  Mat6 P_ = Mat6::Zero();
  double decay_dt_s_ = -1.0, decay_ = 1.0;  // e^(-dt/τ) for the last dt
};

}  // namespace headingd::core
