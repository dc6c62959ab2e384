#include "headingd/core/gyro_bias_estimator.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace headingd::core {

namespace {

// The in-motion measurement is made from the turns of this much time.
constexpr double kMotionWindowS = 0.1;

// χ²(3) at 99 %: a still block's bias further from the estimate than this (in their joint
// covariance) counts as a less certain block.
constexpr double kBlockNisLimit = 11.34;

// Innovations are clipped to the largest plausible bias: one wild sample (a knock, the
// first moments of a motion) moves the estimate at most that far.
template <typename V>
V clipped(const V& e, double limit) {
  return e.cwiseMax(-limit).cwiseMin(limit);
}

DriftingBias::Params driftingBiasParams(const EstimatorParams& p) {
  // Per axis a quarter of the clamp on the magnitude (0.05 rad/s with the default 0.2):
  // 6 deg/s on one axis is 2.1 sigma, and the clamp 4 sigma of one axis.
  return {p.bias_walk_rad_s_per_sqrt_s, p.bias_instability_rad_s, p.bias_instability_time_s,
          0.0625 * p.bias_max_rad_s * p.bias_max_rad_s};
}

}  // namespace

GyroBiasEstimator::GyroBiasEstimator(const EstimatorParams& p)
    : p_(p),
      rest_(p),
      state_(driftingBiasParams(p)),
      P_(state_.covariance()),
      horizontal_rows_(p.accel_prefilter_time_constant_s),
      spread_{TurnSpread(tiltTimeConstantS(p)), TurnSpread(tiltTimeConstantS(p))},
      before_last_block_{state_, 0.0, 0, {}, false} {}

const Vec3& GyroBiasEstimator::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT, double dt_s) {
  state_.predict(dt_s);
  // What the state was before the last block drifts alike, so that it can take its place.
  before_last_block_.state.predict(dt_s);
  settle();
  switch (rest_.update(gyro_rad_s, accel_m_s2, mag_uT, dt_s)) {
    case RestDetector::News::kNone: return bias_;
    case RestDetector::News::kNewBlock:
      before_last_block_ = {state_, rest_seconds_, still_blocks_, previous_outlier_, has_previous_outlier_};
      break;
    case RestDetector::News::kLastBlockWithdrawn: restoreBeforeLastBlock(); return bias_;
    case RestDetector::News::kLastBlockRevised:
      // Nothing else changed the estimate since: the sensor was at rest, where the in-motion
      // update does not learn.
      restoreBeforeLastBlock();
      break;
  }
  // A still block measures the bias: y = its mean rate less its measured turn, H = I, and W
  // its own covariance, but no less than N / T for a block of length T (N = τ² walk²: the
  // estimate follows a changing bias at rest with time constant τ at most).
  const RestBlock& block = rest_.block();
  rest_seconds_ += block.duration_s;
  ++still_blocks_;
  const double tau_walk = p_.bias_time_constant_s * p_.bias_walk_rad_s_per_sqrt_s;
  Mat3 W = block.covariance;
  W.diagonal() = W.diagonal().cwiseMax(tau_walk * tau_walk / block.duration_s);
  const Vec3 innovation = clipped(Vec3(block.bias_rad_s - bias_), p_.bias_max_rad_s);
  Mat3 S = P_ + W;
  // A block that disagrees with the estimate far beyond both their covariances (normalised
  // innovation squared above the 99 % point of χ²(3)) either had a turn its vectors did not
  // measure right (a hand's slow drift with its lever arm's accelerations) or shows that the
  // bias has changed (a temperature step). One such block counts with the spread it shows
  // (S scaled to make its NIS 3) instead of moving the estimate by all of it; the next block
  // decides: if it agrees with the outlier, the bias changed, and the estimate's covariance
  // opens up to the outliers' difference from it, so that the change is learned at once.
  const double nis = innovation.dot(S.ldlt().solve(innovation));
  if (nis > kBlockNisLimit) {
    const Vec3 between = block.bias_rad_s - previous_outlier_.bias_rad_s;
    const bool confirmed = has_previous_outlier_ &&
                           between.dot((W + previous_outlier_.covariance).ldlt().solve(between)) <= kBlockNisLimit;
    if (confirmed) {
      state_.openUp(innovation);
      P_ = state_.covariance();
      S = P_ + W;
      has_previous_outlier_ = false;
    } else {
      previous_outlier_ = {block.bias_rad_s, block.duration_s, W};
      has_previous_outlier_ = true;
      S *= nis / 3.0;
    }
  } else {
    has_previous_outlier_ = false;
  }
  state_.correct<3>(Mat3::Identity(), S, innovation);
  settle();
  return bias_;
}

void GyroBiasEstimator::restoreBeforeLastBlock() {
  const StateBeforeBlock& before = before_last_block_;
  state_ = before.state;
  settle();
  rest_seconds_ = before.rest_seconds;
  still_blocks_ = before.still_blocks;
  previous_outlier_ = before.previous_outlier;
  has_previous_outlier_ = before.has_previous_outlier;
}

GyroBiasEstimator::TurnSpread::TurnSpread(double correlation_time_s)
    : correlation_time_s(correlation_time_s), correlated(correlation_time_s) {}

void GyroBiasEstimator::TurnSpread::add(double turn_rate_rad_s, double window_s) {
  const double value = correlated.update(turn_rate_rad_s, window_s);
  elapsed_s += window_s;
  // Running means (weight T/t) until the low-pass's weight over 10 τ_c is the larger.
  const double weight =
      startedLowPassWeight(elapsed_s, window_s, 1.0 - lowPassAlpha(window_s, 10.0 * correlation_time_s));
  const auto track = [weight](double x, double& m, double& v) {
    const double deviation = x - m;
    m += weight * deviation;
    v += weight * ((1.0 - weight) * deviation * deviation - v);
  };
  track(value, mean, variance);
  track(turn_rate_rad_s, raw_mean, raw_variance);
}

double GyroBiasEstimator::TurnSpread::windowVariance(double window_s) const {
  if (elapsed_s < 3.0 * correlation_time_s) return std::numeric_limits<double>::infinity();
  return std::max(raw_variance, variance * 2.0 * correlation_time_s / window_s);
}

void GyroBiasEstimator::addTiltCorrection(const Eigen::Vector2d& turn_rad, const Quat& q_nb, double dt_s,
                                          bool measures_bias) {
  window_s_ += dt_s;
  since_update_s_ += dt_s;
  if (measures_bias) {
    measuring_s_ += dt_s;
    window_turn_rad_ += turn_rad;
  }
  if (window_s_ < kMotionWindowS) return;
  // The horizontal rows of R(q), low-passed as the turns are (their lag is the gravity
  // filters'): e_xᵀ R and e_yᵀ R written out.
  const double w = q_nb.w(), x = q_nb.x(), y = q_nb.y(), z = q_nb.z();
  Eigen::Matrix<double, 2, 3> rows;
  rows << 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),  //
      2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x);
  horizontal_rows_.update(rows, window_s_);
  if (measuring_s_ >= window_s_) {
    for (int i = 0; i < 2; ++i) spread_[i].add(window_turn_rad_(i) / window_s_, window_s_);
    // The model's H, the low-passed rows, is the turns' lag only while the attitude stays
    // near its low-passed value; while the sensor turns on, the turns follow the rows of
    // some other moment and "explain" a bias that is not there.
    const double moved = (rows - horizontal_rows_.value()).norm();
    if (p_.bias_motion_time_constant_s > 0.0 && moved <= p_.bias_motion_max_attitude_change) updateFromWindow();
  }
  window_s_ = measuring_s_ = 0.0;
  window_turn_rad_.setZero();
}

void GyroBiasEstimator::updateFromWindow() {
  // Over a window of length T the turns sum to -R̄_h β T: y = -Σturn / T, H = R̄_h, W the
  // larger of the turns' spread (header) and N / T (N = τ² walk²: the estimate follows a
  // changing bias with time constant τ at most).
  const double W0 = spread_[0].windowVariance(window_s_), W1 = spread_[1].windowVariance(window_s_);
  if (!std::isfinite(W0) || !std::isfinite(W1)) return;
  const Eigen::Matrix<double, 2, 3>& H = horizontal_rows_.value();
  const double tau_walk = p_.bias_motion_time_constant_s * p_.bias_walk_rad_s_per_sqrt_s;
  const double nominal = tau_walk * tau_walk / window_s_;
  Eigen::Matrix2d S = H * P_ * H.transpose();
  // The turns answer a change of the estimate only through the tilt's lag τ_c, so the update
  // is a loop: an integrator (the bias) behind a first-order lag, which rings or overshoots
  // when the integrator's time constant is short against τ_c (s² τ_c + s + 1/τ_i = 0: damping
  // ratio ½ √(τ_i / τ_c)). While P is large (the first windows, nothing yet known) the Kalman
  // gain alone would move the estimate within a window or two. So each component's gain is
  // at most t / (k τ_c), k = bias_motion_min_tilt_lags, for the time t since the previous
  // update (the turns have followed the last change for that long; t = T while every window
  // updates): W ≥ H P Hᵀ (k τ_c / t - 1).
  const double loop_s = p_.bias_motion_min_tilt_lags * tiltTimeConstantS(p_);
  const double lag_factor = loop_s > 0.0 ? std::max(0.0, loop_s / std::min(since_update_s_, loop_s) - 1.0) : 0.0;
  since_update_s_ = 0.0;
  S(0, 0) += std::max({nominal, W0, lag_factor * S(0, 0)});
  S(1, 1) += std::max({nominal, W1, lag_factor * S(1, 1)});
  const Eigen::Vector2d innovation = -window_turn_rad_ / window_s_;  // = H (b - b̂)
  state_.correct<2>(H, S, clipped(innovation, p_.bias_max_rad_s));
  settle();
}

bool GyroBiasEstimator::addMeasurement(const Linearised<3>& measurement, double max_nis) {
  const Mat3 H = measurement.jacobian.block<3, 3>(0, error_state::kGyroBias);
  const Mat3 S = H * P_ * H.transpose() + measurement.noise_covariance;
  const Vec3& innovation = measurement.residual;
  if (innovation.dot(S.ldlt().solve(innovation)) > max_nis) return false;
  state_.correct<3>(H, S, innovation);
  settle();
  return true;
}

void GyroBiasEstimator::reverseTime() {
  state_.negate();
  settle();
  rest_ = RestDetector(p_);
  before_last_block_ = {state_, rest_seconds_, still_blocks_, {}, false};
  has_previous_outlier_ = false;
  window_s_ = measuring_s_ = since_update_s_ = 0.0;
  window_turn_rad_.setZero();
}

void GyroBiasEstimator::settle() {
  // A larger estimate means rest or motion was misjudged: keep it at the plausible edge.
  state_.clampTo(p_.bias_max_rad_s);
  bias_ = state_.bias();
  P_ = state_.covariance();
}

}  // namespace headingd::core
