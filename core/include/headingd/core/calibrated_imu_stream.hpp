#pragma once
// A calibration applied to the IMU's samples as they come, its magnetometer part only while
// MagCalibrationFit says it still describes the sensor.
#include <cstdint>

#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/imu_sample.hpp"
#include "headingd/core/mag_calibration_fit.hpp"

namespace headingd::core {

// An ImuCorrection applied to a stream of samples, with the magnetometer part checked by
// MagCalibrationFit: while the calibration no longer fits, the raw magnetometer reading
// goes to the estimator (gyro and accelerometer corrections are always applied).
class CalibratedImuStream {
 public:
  CalibratedImuStream() = default;  // no calibration: samples pass unchanged
  explicit CalibratedImuStream(const ImuCalibration& c, const MagCalibrationFitParams& p = {})
      : correction_(c), fit_(p, c.mag.field_norm_uT), calibrated_(true) {}

  ImuSample apply(const ImuSample& raw);
  const MagCalibrationFit& magFit() const { return fit_; }

 private:
  ImuCorrection correction_;
  MagCalibrationFit fit_;
  bool calibrated_ = false;
  std::int64_t last_mag_t_ns_ = 0;
  bool have_last_mag_ = false;
};

}  // namespace headingd::core
