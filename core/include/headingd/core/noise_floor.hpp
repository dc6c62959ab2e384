#pragma once
// The noise level of a signal, learned from the data: the lowest RMS of the last minute.
//
// Why: fixed thresholds for "at rest" or "field disturbed" only suit the sensor they were
// tuned on. A consumer MEMS gyro can be ten times noisier than a lab IMU; with a fixed
// threshold such a sensor never looks at rest (no bias estimate) and its magnetometer always
// looks disturbed (no heading updates). The quietest recent RMS is the sensor's own noise;
// thresholds become a multiple of it, never below their configured minimum. A minimum over
// a sliding window (rather than a running minimum with a leak) forgets a noisier past within
// the window and cannot be pulled up by a disturbance that lasts less than the window.
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

namespace headingd::core {

class NoiseFloor {
 public:
  // warm_up_s: the RMS filters feeding this need that long before their values mean anything.
  explicit NoiseFloor(double warm_up_s) : warm_up_s_(warm_up_s) { bins_.fill(kNone); }

  void update(double rms, double dt_s) {
    elapsed_s_ += dt_s;
    if (elapsed_s_ < warm_up_s_) return;
    current_ = std::min(current_, rms);
    bin_elapsed_s_ += dt_s;
    if (bin_elapsed_s_ >= kBinSeconds) {  // close this second's bin
      bins_[next_] = current_;
      next_ = (next_ + 1) % bins_.size();
      current_ = kNone;
      bin_elapsed_s_ = 0.0;
      closed_minimum_ = *std::min_element(bins_.begin(), bins_.end());  // once a second, not per sample
    }
  }
  // +∞ until the warm-up is over.
  double value() const { return std::min(current_, closed_minimum_); }
  // factor · floor, at least `minimum` and at most `maximum`; `minimum` while nothing is known.
  double threshold(double factor, double minimum, double maximum) const {
    const double floor = value();
    if (floor == kNone) return minimum;
    return std::clamp(factor * floor, minimum, maximum);
  }

 private:
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  static constexpr double kBinSeconds = 1.0;
  double warm_up_s_;
  double elapsed_s_ = 0.0;
  double bin_elapsed_s_ = 0.0;
  double current_ = kNone;
  std::array<double, 60> bins_;  // one minimum per second, the last minute
  std::size_t next_ = 0;
  double closed_minimum_ = kNone;  // minimum of bins_
};

}  // namespace headingd::core
