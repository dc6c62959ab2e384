#pragma once
// First-order low-pass filter of Henriksson §2.3.
#include <algorithm>
#include <cmath>
#include <type_traits>

namespace headingd::core {

// Henriksson eq. 2.17: α for time constant τ at the actual sample period T_s, so that the
// filter keeps its time constant when the sample rate differs from the thesis' 121 Hz.
inline double lowPassAlpha(double sample_period_s, double time_constant_s) {
  const double x = sample_period_s / (time_constant_s + sample_period_s);
  // The filters run at every sample with x ≪ 1; a 4th-order series is exact to 1e-12 there
  // and costs a tenth of std::exp, which the estimator would call a dozen times per sample.
  if (x < 0.01) return 1.0 - x * (1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0))));
  return std::exp(-x);
}

// exp(-T/τ): the exact decay of a continuous-time process over a period T (where
// lowPassAlpha is eq. 2.17's).
inline double expDecay(double sample_period_s, double time_constant_s) {
  return std::exp(-sample_period_s / time_constant_s);
}

// The weight of a new sample in a mean that starts as the running mean of the samples so far
// (weight dt/t after t seconds of them, this sample's dt included) and becomes a low-pass of
// weight low_pass_weight once that weighs more: the first samples count no more than later
// ones, and no single early sample stands for a whole time constant.
inline double startedLowPassWeight(double seen_s, double dt_s, double low_pass_weight) {
  return seen_s > 0.0 ? std::max(dt_s / seen_s, low_pass_weight) : low_pass_weight;
}

// A coefficient of one time constant, kept for the last sample period: the period comes
// from timestamps and is the same from one sample to the next on most sensors, and the
// estimator uses a dozen of these per sample (no std::exp each time).
template <double (*Coefficient)(double sample_period_s, double time_constant_s)>
class PerPeriod {
 public:
  explicit PerPeriod(double time_constant_s) : time_constant_s_(time_constant_s) {}
  double operator()(double sample_period_s) {
    if (sample_period_s != sample_period_s_) {
      sample_period_s_ = sample_period_s;
      value_ = Coefficient(sample_period_s, time_constant_s_);
    }
    return value_;
  }

 private:
  double time_constant_s_;
  double sample_period_s_ = -1.0;  // no period yet
  double value_ = 0.0;
};

using LowPassAlpha = PerPeriod<lowPassAlpha>;
using ExpDecay = PerPeriod<expDecay>;

// Henriksson eq. 2.13: y[k] = α y[k-1] + (1-α) x[k]. The first input initialises y.
template <typename T>
class LowPass {
 public:
  explicit LowPass(double time_constant_s) : alpha_(time_constant_s) {}

  const T& update(const T& x, double sample_period_s) {
    if (!initialised_) {
      y_ = x;
      initialised_ = true;
    } else {
      const double alpha = alpha_(sample_period_s);
      y_ = alpha * y_ + (1.0 - alpha) * x;
    }
    return y_;
  }
  const T& value() const { return y_; }
  bool initialised() const { return initialised_; }
  void reset(const T& y) {
    y_ = y;
    initialised_ = true;
  }

 private:
  static T zero() {
    if constexpr (std::is_arithmetic_v<T>) {
      return T(0);
    } else {
      return T::Zero();  // Eigen types are not zeroed by value-initialisation
    }
  }

  LowPassAlpha alpha_;
  T y_ = zero();
  bool initialised_ = false;
};

}  // namespace headingd::core
