#pragma once
// Gyroscope bias from rest.
//
// Method: a rest detector (gyro and accelerometer both steady over a window) gates a
// low-pass filter of the raw gyro. Why this one: at rest the true rate is zero (Earth's
// 15°/h is far below the noise of body-worn MEMS gyros), so the mean rate *is* the bias and
// needs no model; a person wearing the device stands still often (traffic lights, pauses),
// and BROAD's trials begin and end at rest. Estimating the bias in motion needs an
// observable reference (accelerometer for roll/pitch, magnetometer for yaw) whose errors
// (accelerations, disturbed fields) would leak into the bias; that is the MAGYQ work of a
// later roadmap step. Between rests the last estimate is held.
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/noise_floor.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// Rest: for at least rest_min_duration_s, the RMS deviation of gyro and accelerometer from
// their low-passed means stays below the thresholds (the gyro's: rest_gyro_threshold_rad_s
// or 2.5 times the gyro's own learned noise floor, whichever is larger, up to
// rest_gyro_max_threshold_rad_s; the accelerometer's stays absolute, since it is what tells
// a person standing from one moving) (a variance test, so that one noisy
// sample does not end a rest), and the mean rate itself is close to the current bias (a
// slow steady turn is not rest).
class RestDetector {
 public:
  explicit RestDetector(const EstimatorParams& p)
      : p_(p),
        gyro_mean_(p.rest_filter_time_constant_s),
        accel_mean_(p.rest_filter_time_constant_s),
        gyro_deviation2_(p.rest_filter_time_constant_s),
        accel_deviation2_(p.rest_filter_time_constant_s),
        gyro_floor_(4.0 * p.rest_filter_time_constant_s) {}
  // current_bias: the rate that counts as zero, or nullptr before there is an estimate (a
  // bias larger than the threshold must not keep the detector from ever seeing rest).
  bool update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* current_bias, double dt_s);
  bool atRest() const { return rest_time_s_ >= p_.rest_min_duration_s; }

 private:
  const EstimatorParams& p_;
  LowPass<Vec3> gyro_mean_;
  LowPass<Vec3> accel_mean_;
  LowPass<double> gyro_deviation2_;
  LowPass<double> accel_deviation2_;
  NoiseFloor gyro_floor_;
  double rest_time_s_ = 0.0;
};

class GyroBiasEstimator {
 public:
  explicit GyroBiasEstimator(const EstimatorParams& p) : p_(p), rest_(p), alpha_(p.bias_time_constant_s) {}

  // Feeds one raw sample; returns the current bias estimate.
  const Vec3& update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s);
  const Vec3& bias() const { return bias_; }
  bool atRest() const { return rest_.atRest(); }
  // Seconds of rest the estimate is built on (0 until the first rest).
  double restSeconds() const { return rest_seconds_; }

 private:
  const EstimatorParams& p_;
  RestDetector rest_;
  LowPassAlpha alpha_;  // of the bias low-pass
  Vec3 bias_ = Vec3::Zero();
  double rest_seconds_ = 0.0;
};

}  // namespace headingd::core
