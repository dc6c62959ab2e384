#include "headingd/core/quasi_static_field.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {
namespace {

// The window's sums are kept by adding each new sample and taking off each old one; every so
// many samples they are summed afresh, so that rounding cannot build up over hours.
constexpr std::size_t kRecomputeEvery = 4096;

// The thresholds against the window's noise (header): an RMS of a still field's samples about
// their mean is its noise, estimated from the same samples (to a tenth over 100 of them), so
// 1.5 leaves room for that and for a little slow change; a single sample's distance from the
// reference, 4 of the norm's sigmas, as the disturbance tests' single-sample limits. At most 3
// times the configured values: the noisiest magnetometer we model (a phone's, 1.5 µT per axis
// and sample) needs 1.5 × 1.5 = 2.3 µT of norm RMS against the default 1 µT; a field that
// jitters more than that is not taken for noise.
constexpr double kRmsNoiseFactor = 1.5;
constexpr double kSampleNoiseFactor = 4.0;
constexpr double kMaxOverConfigured = 3.0;

}  // namespace

QuasiStaticFieldDetector::QuasiStaticFieldDetector(const QuasiStaticFieldParams& params) : p_(params) {}

bool QuasiStaticFieldDetector::add(const Vec3& field, const Quat& frame_from_sensor, double dt_s) {
  if (!(p_.window_s > 0.0)) return false;
  // The first sample after a restart closes no interval: what came before is not in the window.
  const double interval_s = size_ == 0 ? 0.0 : dt_s;
  t_s_ += interval_s;
  const double norm = field.norm();
  const Vec3 carried = frame_from_sensor * field;
  double norm_step2 = 0.0, carried_step2 = 0.0;
  if (size_ > 0) {
    const Entry& before = at(size_ - 1);
    norm_step2 = (norm - before.norm) * (norm - before.norm);
    carried_step2 = (carried - before.carried).squaredNorm();
  }
  push({t_s_, norm, carried, norm_step2, carried_step2});
  dropOlderThan(t_s_ - p_.window_s);
  if (!windowFull()) return false;  // nor in a period: a restart or the start ended it

  // Every test compares squares (the estimator calls this at every sample: no square roots).
  const double spread2 = normMeanSquare(sum_norm_ / static_cast<double>(size_));
  const double direction2 = directionMeanSquare();
  const auto threshold2 = [](double configured, double factor, double noise2) {
    return std::clamp(factor * factor * noise2, configured * configured,
                      kMaxOverConfigured * kMaxOverConfigured * configured * configured);
  };
  const double norm_noise2 = normNoise2();
  const double max_norm_rms2 = threshold2(p_.max_norm_rms, kRmsNoiseFactor, norm_noise2);
  const double max_norm_deviation2 = threshold2(p_.max_norm_deviation, kSampleNoiseFactor, norm_noise2);
  const double max_direction_rms2 = threshold2(p_.max_direction_rms, kRmsNoiseFactor, directionNoise2());

  if (in_period_) {
    // Each new sample against ξ_ref (eq. 34), the window against it (eq. 33) and the direction.
    const double deviation = norm - reference_norm_;
    const bool holds = deviation * deviation <= max_norm_deviation2 &&
                       normMeanSquare(reference_norm_) <= max_norm_rms2 && direction2 <= max_direction_rms2;
    if (holds) {
      period_s_ += interval_s;
      total_s_ += interval_s;
    } else {
      in_period_ = false;
      // The next period needs a window of its own: the samples that ended this one are in it.
      wait_until_s_ = t_s_ + p_.window_s;
    }
    return in_period_;
  }
  // Not in a period: the cheap tests first, with the window's own mean norm in place of ξ_ref
  // (a window whose spread about any value is below γ1 has it below γ1 about its mean too).
  if (t_s_ < wait_until_s_ || spread2 > max_norm_rms2 || direction2 > max_direction_rms2) return false;
  return tryStart(max_norm_rms2, max_norm_deviation2);
}

bool QuasiStaticFieldDetector::tryStart(double max_norm_rms2, double max_norm_deviation2) {
  // ξ_ref: the mean norm of the period's first reference_s (MAGYQ §5, N_first).
  const double first_t = at(0).t_s;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < size_ && at(i).t_s <= first_t + p_.reference_s; ++i, ++count) sum += at(i).norm;
  const double reference = sum / static_cast<double>(count);
  // Eq. 34 for every sample of the window; eq. 33 about ξ_ref.
  double latest_outlier_s = -1.0;
  for (std::size_t i = 0; i < size_; ++i) {
    const double deviation = at(i).norm - reference;
    if (deviation * deviation > max_norm_deviation2) latest_outlier_s = at(i).t_s;
  }
  if (latest_outlier_s >= 0.0) {
    wait_until_s_ = latest_outlier_s + p_.window_s;
    return false;
  }
  if (normMeanSquare(reference) > max_norm_rms2) return false;
  in_period_ = true;
  reference_norm_ = reference;
  period_s_ = 0.0;
  ++periods_;
  return true;
}

void QuasiStaticFieldDetector::restart() {
  t_s_ = 0.0;
  head_ = 0;
  size_ = 0;
  recomputeSums();
  wait_until_s_ = 0.0;
  in_period_ = false;
  period_s_ = 0.0;
}

void QuasiStaticFieldDetector::push(const Entry& e) {
  if (size_ == ring_.size()) {  // grows while the window fills at a new rate; then never again
    // A power of two, so that at() wraps with a mask.
    std::vector<Entry> grown(std::max<std::size_t>(64, 2 * ring_.size()), Entry{0.0, 0.0, Vec3::Zero(), 0.0, 0.0});
    for (std::size_t i = 0; i < size_; ++i) grown[i] = at(i);
    ring_ = std::move(grown);
    head_ = 0;
  }
  ring_[(head_ + size_) & (ring_.size() - 1)] = e;
  ++size_;
  sum_norm_ += e.norm;
  sum_norm2_ += e.norm * e.norm;
  sum_carried_ += e.carried;
  sum_carried2_ += e.carried.squaredNorm();
  if (size_ > 1) {  // a first entry (after a restart) has no pair in the window
    sum_norm_step2_ += e.norm_step2;
    sum_carried_step2_ += e.carried_step2;
  }
  if (++pushes_since_recompute_ >= kRecomputeEvery) recomputeSums();
}

void QuasiStaticFieldDetector::dropOlderThan(double t_s) {
  while (size_ > 1 && at(0).t_s <= t_s) {
    const Entry& e = at(0);
    sum_norm_ -= e.norm;
    sum_norm2_ -= e.norm * e.norm;
    sum_carried_ -= e.carried;
    sum_carried2_ -= e.carried.squaredNorm();
    sum_norm_step2_ -= at(1).norm_step2;  // the pair joining the oldest to the next leaves
    sum_carried_step2_ -= at(1).carried_step2;
    head_ = (head_ + 1) & (ring_.size() - 1);
    --size_;
  }
}

void QuasiStaticFieldDetector::recomputeSums() {
  pushes_since_recompute_ = 0;
  sum_norm_ = sum_norm2_ = sum_carried2_ = sum_norm_step2_ = sum_carried_step2_ = 0.0;
  sum_carried_.setZero();
  for (std::size_t i = 0; i < size_; ++i) {
    const Entry& e = at(i);
    sum_norm_ += e.norm;
    sum_norm2_ += e.norm * e.norm;
    sum_carried_ += e.carried;
    sum_carried2_ += e.carried.squaredNorm();
    if (i > 0) {
      sum_norm_step2_ += e.norm_step2;
      sum_carried_step2_ += e.carried_step2;
    }
  }
}

bool QuasiStaticFieldDetector::windowFull() const {
  // The window holds the samples of the last window_s: it is whole once that much time has
  // passed since the restart
  // (to a microsecond: a sum of sample intervals such as 100 × 0.01 s rounds either way).
  return size_ > 1 && t_s_ + 1e-6 >= p_.window_s;
}

double QuasiStaticFieldDetector::normMeanSquare(double reference) const {
  // Σ (n - ξ)² = Σ n² - 2 ξ Σ n + N ξ²
  const double n = static_cast<double>(size_);
  const double sum_sq = sum_norm2_ - 2.0 * reference * sum_norm_ + n * reference * reference;
  return std::max(0.0, sum_sq / n);
}

double QuasiStaticFieldDetector::normNoise2() const {
  return std::max(0.0, sum_norm_step2_ / (2.0 * static_cast<double>(size_ - 1)));
}

double QuasiStaticFieldDetector::directionNoise2() const {
  return std::max(0.0, sum_carried_step2_ / (2.0 * static_cast<double>(size_ - 1)));
}

double QuasiStaticFieldDetector::sampleNoiseSigma() const {
  return size_ > 1 ? std::sqrt(directionNoise2() / 3.0) : 0.0;
}

double QuasiStaticFieldDetector::directionMeanSquare() const {
  // The spread about the mean: mean |c|² - |mean c|².
  const double n = static_cast<double>(size_);
  return std::max(0.0, sum_carried2_ / n - (sum_carried_ / n).squaredNorm());
}

}  // namespace headingd::core
