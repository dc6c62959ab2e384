#include "headingd/core/heading_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace headingd::core {
namespace {

constexpr int kE = 0, kB = 1, kU = 2;

// Standard deviation of an angle uniform on the circle: π/√3 (104°).
const double kUnknownSigmaRad = std::numbers::pi / std::sqrt(3.0);

// The innovations are averaged over this long before they are squared: long enough that a
// consumer magnetometer's white noise (a few degrees per sample at 100 Hz) averages away,
// short against the observer's time constant, whose error is what is left.
constexpr double kInnovationMeanS = 1.0;

}  // namespace

HeadingUncertainty::HeadingUncertainty(const HeadingUncertaintyParams& params)
    : p_(params),
      field_decay_(params.field_correlation_s),
      field_sample_decay_(params.field_correlation_s),
      innovation_mean_decay_(kInnovationMeanS) {}

void HeadingUncertainty::forget() {
  known_ = false;
  // e is undefined until the field sets it: no correlation with b or u is kept.
  P_.row(kE).setZero();
  P_.col(kE).setZero();
}

void HeadingUncertainty::predict(double dt_s, double rate_variance) {
  // b: the gyro bias filter's vertical variance, unless the integral term has learned more
  // (then b's own variance, which only the integral term lowers, is the smaller). Rescaling
  // b's row and column keeps the correlations and P positive semi-definite.
  const double walk = p_.rate_walk_rad_s_per_sqrt_s * p_.rate_walk_rad_s_per_sqrt_s * dt_s;
  const double b_variance = rate_started_ ? std::min(P_(kB, kB) + walk, rate_variance) : rate_variance;
  if (P_(kB, kB) > 0.0 && b_variance != P_(kB, kB)) {
    const double scale = std::sqrt(b_variance / P_(kB, kB));
    P_.row(kB) *= scale;
    P_.col(kB) *= scale;
  } else if (P_(kB, kB) <= 0.0) {
    P_(kB, kB) = b_variance;
  }
  rate_started_ = true;
  // e ← e + b dt.
  if (known_) {
    P_(kE, kE) += 2.0 * dt_s * P_(kE, kB) + dt_s * dt_s * P_(kB, kB);
    P_(kE, kB) += dt_s * P_(kB, kB);
    P_(kE, kU) += dt_s * P_(kB, kU);
    P_(kB, kE) = P_(kE, kB);
    P_(kU, kE) = P_(kE, kU);
  }
  // u ← φ u + w, φ = exp(-dt/T), var w = (1 - φ²) σ_u².
  const double phi = field_decay_(dt_s);
  const double steady =
      p_.field_sigma_rad * p_.field_sigma_rad + innovation_variance_ + p_.set_aside_share * set_aside_variance_;
  if (!field_started_) {
    P_(kU, kU) = steady;  // the first sample: u in its steady state
    field_started_ = true;
    return;
  }
  P_.row(kU) *= phi;
  P_.col(kU) *= phi;
  P_(kU, kU) += (1.0 - phi * phi) * steady;
}

void HeadingUncertainty::observeInnovation(double innovation_rad, double dt_s) {
  set_aside_variance_ -= (1.0 - field_sample_decay_(dt_s)) * set_aside_variance_;  // a used sample: 0
  // Both averages start as running means: seeded with the first sample instead, one
  // magnetometer sample's noise (5-10 deg on a consumer part) stood for the innovations' spread
  // for a whole field_correlation_s and lifted the sigma of every run for a minute. And the
  // spread waits for a full second of innovations, the time the mean needs to average that
  // noise away.
  innovation_seen_s_ += dt_s;
  innovation_mean_rad_ += startedLowPassWeight(innovation_seen_s_, dt_s, 1.0 - innovation_mean_decay_(dt_s)) *
                          (innovation_rad - innovation_mean_rad_);
  if (innovation_seen_s_ < kInnovationMeanS) return;
  const double spread_seen_s = innovation_seen_s_ - kInnovationMeanS + dt_s;
  const double squared = innovation_mean_rad_ * innovation_mean_rad_;
  innovation_variance_ +=
      startedLowPassWeight(spread_seen_s, dt_s, 1.0 - field_sample_decay_(dt_s)) * (squared - innovation_variance_);
}

void HeadingUncertainty::observeSetAside(double innovation_rad, double dt_s) {
  // Capped: a field turned by more than 90° says no more about the heading than one at 90°.
  const double capped = std::min(std::abs(innovation_rad), 0.5 * std::numbers::pi);
  set_aside_variance_ += (1.0 - field_sample_decay_(dt_s)) * (capped * capped - set_aside_variance_);
}

void HeadingUncertainty::correct(double gain, double rate_gain) {
  // x ← A x with e ← (1 - K) e + K u (innovation = ψ_mm - ψ = u - e) and b ← b + g (u - e)
  // (the integral term's rate moves by g × innovation): P ← A P Aᵀ.
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A(kE, kE) = 1.0 - gain;
  A(kE, kU) = gain;
  A(kB, kE) = -rate_gain;
  A(kB, kU) = rate_gain;
  if (!known_) {
    // The field sets the heading outright: e = u from now on.
    A(kE, kE) = 0.0;
    A(kE, kU) = 1.0;
    known_ = true;
  }
  P_ = A * P_ * A.transpose();
}

double HeadingUncertainty::sigmaRad() const {
  return known_ ? std::sqrt(std::max(P_(kE, kE), 0.0)) : kUnknownSigmaRad;
}

double HeadingUncertainty::rateSigmaRadS() const { return std::sqrt(std::max(P_(kB, kB), 0.0)); }

}  // namespace headingd::core
