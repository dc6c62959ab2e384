#include "headingd/core/heading_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace headingd::core {
namespace {

constexpr int kE = 0, kB = 1, kA = 2, kP = 3;

// Standard deviation of an angle uniform on the circle: π/√3 (104°).
const double kUnknownSigmaRad = std::numbers::pi / std::sqrt(3.0);

// The innovations are averaged over this long before they are squared: long enough that a
// consumer magnetometer's white noise (a few degrees per sample at 100 Hz) averages away,
// short against the observer's time constant, whose error is what is left.
constexpr double kInnovationMeanS = 1.0;

// The innovations' noise variance at least: keeps the filter that has seen them from dividing
// by zero on a noiseless (simulated) sensor.
constexpr double kMinNoiseVariance = 1e-8;  // rad², (0.006°)²

// Sets b's variance, keeping its correlations (P stays positive semi-definite); returns the
// factor b's standard deviation changed by.
double setRateVariance(Eigen::Matrix4d& P, double variance) {
  if (P(kB, kB) <= 0.0) {
    P(kB, kB) = variance;
    return 1.0;
  }
  if (variance == P(kB, kB)) return 1.0;
  const double scale = std::sqrt(variance / P(kB, kB));
  P.row(kB) *= scale;
  P.col(kB) *= scale;
  return scale;
}

// e ← e + b dt: P ← A P Aᵀ with A = I + dt (row e, column b).
void integrateRate(Eigen::Matrix4d& P, double dt_s) {
  P.row(kE) += dt_s * P.row(kB);
  P.col(kE) += dt_s * P.col(kB);
}

// x_i ← φ x_i + w, var w = (1 - φ²) steady.
void decay(Eigen::Matrix4d& P, int i, double phi, double steady) {
  P.row(i) *= phi;
  P.col(i) *= phi;
  P(i, i) += (1.0 - phi * phi) * steady;
}

}  // namespace

HeadingUncertainty::HeadingUncertainty(const HeadingUncertaintyParams& params)
    : p_(params),
      field_decay_(params.field_correlation_s),
      field_sample_decay_(params.field_correlation_s),
      innovation_mean_decay_(kInnovationMeanS) {}

void HeadingUncertainty::forget() {
  known_ = false;
  // e is undefined until the field sets it: no correlation with b or u is kept.
  for (Eigen::Matrix4d* P : {&P_, &shown_P_}) {
    P->row(kE).setZero();
    P->col(kE).setZero();
  }
  shown_x_(kE) = 0.0;
}

void HeadingUncertainty::predict(double dt_s, double rate_variance, double attitude_turn_rad) {
  // b: the gyro bias filter's vertical variance, unless the integral term (or, for the
  // filter that has seen the innovations, the field) has shown more: then b's own variance,
  // which only they lower, is the smaller.
  const double walk = p_.rate_walk_rad_s_per_sqrt_s * p_.rate_walk_rad_s_per_sqrt_s * dt_s;
  const auto b_variance = [&](const Eigen::Matrix4d& P) {
    return rate_started_ ? std::min(P(kB, kB) + walk, rate_variance) : rate_variance;
  };
  setRateVariance(P_, b_variance(P_));
  shown_x_(kB) *= setRateVariance(shown_P_, b_variance(shown_P_));
  rate_started_ = true;
  if (known_) {
    integrateRate(P_, dt_s);
    integrateRate(shown_P_, dt_s);
    shown_x_(kE) += dt_s * shown_x_(kB);
  }
  const double phi_place = field_decay_(dt_s);
  // Most samples turn by nothing (NetTurn counts in steps): no exp for them.
  const double phi_attitude = p_.field_turn_rad <= 0.0  ? phi_place
                              : attitude_turn_rad > 0.0 ? std::exp(-attitude_turn_rad / p_.field_turn_rad)
                                                        : 1.0;
  const double floor = p_.field_sigma_rad * p_.field_sigma_rad;
  const double place = innovation_variance_ + p_.set_aside_share * set_aside_variance_;
  if (!field_started_) {  // the first sample: a and p in their steady states
    P_(kA, kA) = shown_P_(kA, kA) = floor;
    P_(kP, kP) = shown_P_(kP, kP) = place;
    field_started_ = true;
    return;
  }
  for (Eigen::Matrix4d* P : {&P_, &shown_P_}) {
    decay(*P, kA, phi_attitude, floor);
    decay(*P, kP, phi_place, place);
  }
  shown_x_(kA) *= phi_attitude;
  shown_x_(kP) *= phi_place;
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
  const double about_mean = innovation_rad - innovation_mean_rad_;
  innovation_noise_variance_ += startedLowPassWeight(innovation_seen_s_, dt_s, 1.0 - field_sample_decay_(dt_s)) *
                                (about_mean * about_mean - innovation_noise_variance_);
  // The filter that has seen the innovations waits for their noise as the spread does: from
  // a few samples their spread about their mean is near zero, and the first innovations,
  // taken as noiseless, "showed" a rate error of a rad/s that took minutes to unlearn.
  if (innovation_seen_s_ < kInnovationMeanS) return;
  showInnovation(innovation_rad, dt_s);
  const double spread_seen_s = innovation_seen_s_ - kInnovationMeanS + dt_s;
  const double squared = innovation_mean_rad_ * innovation_mean_rad_;
  innovation_variance_ +=
      startedLowPassWeight(spread_seen_s, dt_s, 1.0 - field_sample_decay_(dt_s)) * (squared - innovation_variance_);
}

void HeadingUncertainty::showInnovation(double innovation_rad, double dt_s) {
  // ν = a + p - e + n, H = (-1, 0, 1, 1) (written out below). n's variance counts once per
  // kInnovationMeanS: the innovations' fast part (magnetometer noise, the stride's tilt error
  // through the dip) is not white from sample to sample, and counted per sample it would say
  // the field's mean error known a hundred times too soon.
  if (!known_) return;
  const double noise =
      std::max(innovation_noise_variance_, kMinNoiseVariance) * std::max(kInnovationMeanS / std::max(dt_s, 1e-6), 1.0);
  const Eigen::Vector4d PHt = shown_P_.col(kA) + shown_P_.col(kP) - shown_P_.col(kE);
  const double S = PHt(kA) + PHt(kP) - PHt(kE) + noise;
  shown_x_ += PHt * ((innovation_rad - shown_x_(kA) - shown_x_(kP) + shown_x_(kE)) / S);
  // P - P Hᵀ H P / S: a symmetric rank-one downdate.
  shown_P_.noalias() -= PHt * (PHt.transpose() / S);
}

void HeadingUncertainty::observeSetAside(double innovation_rad, double dt_s) {
  // Capped: a field turned by more than 90° says no more about the heading than one at 90°.
  const double capped = std::min(std::abs(innovation_rad), 0.5 * std::numbers::pi);
  set_aside_variance_ += (1.0 - field_sample_decay_(dt_s)) * (capped * capped - set_aside_variance_);
}

void HeadingUncertainty::correct(double gain, double rate_gain) {
  // x ← A x with e ← (1 - K) e + K u (u = a + p; innovation = ψ_mm - ψ = u - e) and
  // b ← b + g (u - e) (the integral term's rate moves by g × innovation): P ← A P Aᵀ. The
  // field sets the first heading outright: e = u from then on.
  const double keep = known_ ? 1.0 - gain : 0.0;
  const double take = known_ ? gain : 1.0;
  known_ = true;
  const auto transform = [&](auto&& e, auto&& b, const auto& a, const auto& p) {  // rows, then columns
    b += rate_gain * (a + p - e);
    e = keep * e + take * (a + p);
  };
  for (Eigen::Matrix4d* P : {&P_, &shown_P_}) {
    transform(P->row(kE), P->row(kB), P->row(kA), P->row(kP));
    transform(P->col(kE), P->col(kB), P->col(kA), P->col(kP));
  }
  transform(shown_x_(kE), shown_x_(kB), shown_x_(kA), shown_x_(kP));
}

double HeadingUncertainty::sigmaRad() const {
  if (!known_) return kUnknownSigmaRad;
  // The expected squared error given the innovations: the posterior variance plus the
  // estimated error's square (ê is not taken off the heading).
  return std::sqrt(std::max(shown_P_(kE, kE), 0.0) + shown_x_(kE) * shown_x_(kE));
}

double HeadingUncertainty::priorSigmaRad() const {
  return known_ ? std::sqrt(std::max(P_(kE, kE), 0.0)) : kUnknownSigmaRad;
}

double HeadingUncertainty::rateSigmaRadS() const { return std::sqrt(std::max(P_(kB, kB), 0.0)); }

double HeadingUncertainty::shownRateRadS() const { return shown_x_(kB); }

double HeadingUncertainty::shownRateSigmaRadS() const { return std::sqrt(std::max(shown_P_(kB, kB), 0.0)); }

}  // namespace headingd::core
